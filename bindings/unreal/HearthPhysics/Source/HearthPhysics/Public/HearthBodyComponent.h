// UHearthBodyComponent - gives its owner a Hearth body shaped like the owner's root primitive
// (box, sphere or capsule component, else the primitive's bounding box) and moves the owner to
// the body's interpolated pose every frame.
// NOT COMPILED in the Hearth repository (no Unreal Engine there); see ../../../README.md.
#pragma once

#include "CoreMinimal.h"
#include "Components/ActorComponent.h"
#include "hearth.h"
#include "HearthBodyComponent.generated.h"

UCLASS(ClassGroup = (Physics), meta = (BlueprintSpawnableComponent))
class HEARTHPHYSICS_API UHearthBodyComponent : public UActorComponent
{
	GENERATED_BODY()

public:
	/** Moves under gravity and contacts; off makes a static body (floors, walls). */
	UPROPERTY(EditAnywhere, Category = "Hearth")
	bool bDynamic = true;

	/** g/cm³, as Unreal physical materials (1 = water). */
	UPROPERTY(EditAnywhere, Category = "Hearth", meta = (ClampMin = "0"))
	float Density = 1.0f;

	UPROPERTY(EditAnywhere, Category = "Hearth", meta = (ClampMin = "0"))
	float Friction = 0.6f;

	UPROPERTY(EditAnywhere, Category = "Hearth", meta = (ClampMin = "0"))
	float Restitution = 0.0f;

	/** Force in Unreal units (kg·cm/s²) for the next step. */
	UFUNCTION(BlueprintCallable, Category = "Hearth")
	void AddForce(FVector Force);

	/** cm/s. */
	UFUNCTION(BlueprintCallable, Category = "Hearth")
	FVector GetLinearVelocity() const;

	/** Called by UHearthWorldSubsystem each frame with the interpolated pose (cm). */
	void ApplyHearthPose(const FVector& Location, const FQuat& Rotation);

	HearthBodyId GetBodyId() const { return Body; }

protected:
	virtual void BeginPlay() override;
	virtual void EndPlay(const EEndPlayReason::Type Reason) override;

private:
	HearthBodyId Body{0, 0};
};
