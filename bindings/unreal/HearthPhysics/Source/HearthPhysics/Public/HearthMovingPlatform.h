// AHearthMovingPlatform - the plug-in's example actor: a platform that travels back and forth
// (and may turn) as a kinematic Hearth body, carrying whatever dynamic bodies stand on it.
// NOT COMPILED in the Hearth repository (no Unreal Engine there); see ../../../README.md.
//
// Drop it in a level, put a few actors with a Hearth Body component (Dynamic) above it and
// press Play. The actor moves itself every frame like any gameplay code would; its Hearth Body
// (Kinematic) follows through the fixed steps and pushes what it touches.
#pragma once

#include "CoreMinimal.h"
#include "GameFramework/Actor.h"
#include "HearthMovingPlatform.generated.h"

class UHearthBodyComponent;
class UStaticMeshComponent;

UCLASS(Blueprintable)
class HEARTHPHYSICS_API AHearthMovingPlatform : public AActor
{
	GENERATED_BODY()

public:
	AHearthMovingPlatform();

	/** The platform's mesh and root (Unreal's 1 m engine cube, scaled to 4 × 4 × 0.2 m). */
	UPROPERTY(VisibleAnywhere, BlueprintReadOnly, Category = "Hearth")
	TObjectPtr<UStaticMeshComponent> Mesh;

	/** Its kinematic Hearth body. */
	UPROPERTY(VisibleAnywhere, BlueprintReadOnly, Category = "Hearth")
	TObjectPtr<UHearthBodyComponent> Body;

	/** Where the trip ends, relative to where the platform starts (cm). */
	UPROPERTY(EditAnywhere, BlueprintReadWrite, Category = "Hearth", meta = (MakeEditWidget = true))
	FVector TravelOffset = FVector(0.0, 600.0, 0.0);

	/** Seconds for a trip there and back (eased at both ends). */
	UPROPERTY(EditAnywhere, BlueprintReadWrite, Category = "Hearth", meta = (ClampMin = "0.1"))
	float CycleSeconds = 6.0f;

	/** Turn while travelling (degrees per second about the vertical). */
	UPROPERTY(EditAnywhere, BlueprintReadWrite, Category = "Hearth")
	float YawDegreesPerSecond = 0.0f;

	/** Stops and restarts the trip. */
	UFUNCTION(BlueprintCallable, Category = "Hearth")
	void SetMoving(bool bMove) { bMoving = bMove; }

	virtual void BeginPlay() override;
	virtual void Tick(float DeltaSeconds) override;

private:
	FVector StartLocation = FVector::ZeroVector;
	FRotator StartRotation = FRotator::ZeroRotator;
	double Elapsed = 0.0;
	bool bMoving = true;
};
