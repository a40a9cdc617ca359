// UHearthBodyComponent - gives its owner a Hearth body made of the collision of the owner's root
// primitive (its simple-collision spheres, boxes, capsules and convex elements; on static and
// kinematic bodies optionally its complex collision, the triangles) or, on a landscape, of its
// height data; and keeps actor and body in step in both directions.
// NOT COMPILED in the Hearth repository (no Unreal Engine there); see ../../../README.md.
//
// All values in and out are Unreal's: centimetres, kg, seconds, forces in kg·cm/s² (Unreal's
// "Newtons" in AddForce), torques in kg·cm²/s², angular velocities in rad/s, Z up. The
// conversions are HearthConversion.h; the semantics (forces last for their frame, impulses
// act at once, kinematic bodies follow their actor, gameplay moves teleport) are
// HearthCore::FSimulation's, tested in the Hearth repository.
#pragma once

#include "Components/ActorComponent.h"
#include "CoreMinimal.h"
#include "hearth.h"
#include "HearthBodyComponent.generated.h"

namespace HearthCore
{
class FSimulation;
}
class UPrimitiveComponent;
class UHearthWorldSubsystem;

UENUM(BlueprintType)
enum class EHearthBodyType : uint8
{
	/** Never moves (floors, walls). Gameplay may still move its actor: the body is teleported. */
	Static,
	/** Follows its actor (moved by gameplay, a timeline, Sequencer) and pushes dynamic bodies:
	 * moving platforms, doors, elevators. */
	Kinematic,
	/** Moves under gravity, forces and contacts; the actor is moved to the body. */
	Dynamic,
};

UCLASS(ClassGroup = (Physics), meta = (BlueprintSpawnableComponent, DisplayName = "Hearth Body"))
class HEARTHPHYSICS_API UHearthBodyComponent : public UActorComponent
{
	GENERATED_BODY()

public:
	UHearthBodyComponent();

	UPROPERTY(EditAnywhere, BlueprintReadOnly, Category = "Hearth")
	EHearthBodyType BodyType = EHearthBodyType::Dynamic;

	/** g/cm³, as Unreal physical materials (1 = water). The mass comes from it and the shapes. */
	UPROPERTY(EditAnywhere, BlueprintReadOnly, Category = "Hearth", meta = (ClampMin = "0.001"))
	float Density = 1.0f;

	/** Coulomb friction while sliding; two touching bodies combine as the geometric mean. */
	UPROPERTY(EditAnywhere, BlueprintReadOnly, Category = "Hearth", meta = (ClampMin = "0"))
	float Friction = 0.6f;

	/** Friction at rest (at least Friction). */
	UPROPERTY(EditAnywhere, BlueprintReadOnly, Category = "Hearth", meta = (ClampMin = "0"))
	float StaticFriction = 0.6f;

	/** Static and kinematic bodies: collide by the static mesh's triangles (its complex
	 * collision, one shared Hearth mesh per asset) instead of its simple-collision elements.
	 * Also on when the mesh's Collision Complexity is "Use Complex Collision As Simple".
	 * Ignored on dynamic bodies (a triangle mesh has no volume, so no mass). */
	UPROPERTY(EditAnywhere, BlueprintReadOnly, Category = "Hearth")
	bool bUseComplexCollision = false;

	/** Bounciness, 0 to 1; two touching bodies take the larger. */
	UPROPERTY(EditAnywhere, BlueprintReadOnly, Category = "Hearth", meta = (ClampMin = "0", ClampMax = "1"))
	float Restitution = 0.0f;

	/** 1/s. */
	UPROPERTY(EditAnywhere, BlueprintReadOnly, Category = "Hearth", meta = (ClampMin = "0"))
	float LinearDamping = 0.0f;

	/** 1/s. */
	UPROPERTY(EditAnywhere, BlueprintReadOnly, Category = "Hearth", meta = (ClampMin = "0"))
	float AngularDamping = 0.0f;

	UPROPERTY(EditAnywhere, BlueprintReadOnly, Category = "Hearth")
	bool bAllowSleep = true;

	// ---- forces: they act for the duration of the frame in which they are added

	/** A force (kg·cm/s²) at the centre of mass for this frame; call it every frame for a steady push. */
	UFUNCTION(BlueprintCallable, Category = "Hearth")
	void AddForce(FVector Force);

	/** A force (kg·cm/s²) at a world location (cm) for this frame. */
	UFUNCTION(BlueprintCallable, Category = "Hearth")
	void AddForceAtLocation(FVector Force, FVector Location);

	/** A torque (kg·cm²/s²) for this frame. */
	UFUNCTION(BlueprintCallable, Category = "Hearth")
	void AddTorqueInRadians(FVector Torque);

	// ---- impulses: they act once, at once

	/** An impulse (kg·cm/s) at the centre of mass; with bVelChange a change of velocity (cm/s). */
	UFUNCTION(BlueprintCallable, Category = "Hearth")
	void AddImpulse(FVector Impulse, bool bVelChange = false);

	/** An impulse (kg·cm/s) at a world location (cm). */
	UFUNCTION(BlueprintCallable, Category = "Hearth")
	void AddImpulseAtLocation(FVector Impulse, FVector Location);

	/** An angular impulse (kg·cm²/s). */
	UFUNCTION(BlueprintCallable, Category = "Hearth")
	void AddAngularImpulseInRadians(FVector Impulse);

	// ---- state

	/** cm/s. */
	UFUNCTION(BlueprintCallable, Category = "Hearth")
	void SetLinearVelocity(FVector Velocity);

	/** cm/s. */
	UFUNCTION(BlueprintPure, Category = "Hearth")
	FVector GetLinearVelocity() const;

	/** rad/s (Unreal's axes and sense of rotation). */
	UFUNCTION(BlueprintCallable, Category = "Hearth")
	void SetAngularVelocityInRadians(FVector AngularVelocity);

	/** rad/s. */
	UFUNCTION(BlueprintPure, Category = "Hearth")
	FVector GetAngularVelocityInRadians() const;

	/** kg (0 for static and kinematic bodies, whose mass is infinite). */
	UFUNCTION(BlueprintPure, Category = "Hearth")
	float GetMass() const;

	UFUNCTION(BlueprintPure, Category = "Hearth")
	bool IsAwake() const;

	UFUNCTION(BlueprintCallable, Category = "Hearth")
	void WakeUp();

	UFUNCTION(BlueprintCallable, Category = "Hearth")
	void PutToSleep();

	// ---- moving

	/** Moves actor and body at once, without sweeping and without interpolating from the old
	 * pose; velocities are kept (a kinematic body stops). */
	UFUNCTION(BlueprintCallable, Category = "Hearth")
	void TeleportTo(FVector Location, FRotator Rotation);

	/** Kinematic bodies: moves the actor, and the body follows it through the coming steps,
	 * pushing what it touches (the same as moving the actor any other way). */
	UFUNCTION(BlueprintCallable, Category = "Hearth")
	void MoveKinematic(FVector Location, FRotator Rotation);

	/** Whether the component has a Hearth body (the world runs and its shapes were made). */
	UFUNCTION(BlueprintPure, Category = "Hearth")
	bool HasBody() const { return Body.generation != 0; }

	// ---- called by UHearthWorldSubsystem every frame

	/** Before the steps: the actor's pose (gameplay moves, kinematic targets). */
	void PushToHearth(HearthCore::FSimulation& Simulation);
	/** After the steps: dynamic bodies move their actor to the interpolated pose. */
	void PullFromHearth(HearthCore::FSimulation& Simulation);

	HearthBodyId GetBodyId() const { return Body; }

protected:
	virtual void BeginPlay() override;
	virtual void EndPlay(const EEndPlayReason::Type Reason) override;

private:
	UPrimitiveComponent* GetRootPrimitive() const;
	HearthCore::FSimulation* GetSimulation() const;
	/** One shape per simple-collision element of the primitive's body setup; returns the count. */
	int32 CreateShapes(HearthCore::FSimulation& Simulation, UPrimitiveComponent* Primitive);
	/** The primitive's complex collision (its triangles) as one mesh shape; true when made. */
	bool CreateMeshShape(HearthCore::FSimulation& Simulation, UPrimitiveComponent* Primitive, const HearthShapeDef& Material);
	/** One heightfield shape per collision component of a landscape; returns the count. */
	int32 CreateLandscapeShapes(HearthCore::FSimulation& Simulation, class ALandscapeProxy* Landscape);
	/** BeginPlay for a landscape actor: a static body of its collision components' heights. */
	void BeginPlayLandscape(UHearthWorldSubsystem& Subsystem, class ALandscapeProxy* Landscape);
	/** The shape material from the component's properties. */
	HearthShapeDef MakeMaterial() const;

	HearthBodyId Body{0, 0};
	bool bWarnedMoveKinematic = false;
};
