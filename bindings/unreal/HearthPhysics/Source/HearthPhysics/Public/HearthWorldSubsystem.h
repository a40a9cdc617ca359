// UHearthWorldSubsystem - one Hearth world per game world, stepped on a fixed time step with
// an accumulator; actors are drawn at the pose interpolated between the last two steps.
// NOT COMPILED in the Hearth repository (no Unreal Engine there); see ../../../README.md.
// All unit and axis conversion is in HearthConversion.h, which is compiled and tested there.
#pragma once

#include "CoreMinimal.h"
#include "Subsystems/WorldSubsystem.h"
#include "HearthConversion.h"
#include "hearth.h"
#include "HearthWorldSubsystem.generated.h"

class UHearthBodyComponent;

UCLASS()
class HEARTHPHYSICS_API UHearthWorldSubsystem : public UTickableWorldSubsystem
{
	GENERATED_BODY()

public:
	virtual void Initialize(FSubsystemCollectionBase& Collection) override;
	virtual void Deinitialize() override;
	virtual void Tick(float DeltaTime) override;
	virtual TStatId GetStatId() const override;
	virtual bool DoesSupportWorldType(const EWorldType::Type WorldType) const override;

	/** Creates the component's body from a Hearth def (metres, Y up) and starts driving it. */
	HearthBodyId AddBody(UHearthBodyComponent* Component, const HearthBodyDef& Def);
	/** Destroys the body and stops driving the component. */
	void RemoveBody(UHearthBodyComponent* Component);
	HearthWorld* GetHearthWorld() const { return World; }

	/** Logs a failed Hearth call with its result name and message; returns true on success. */
	static bool Check(HearthResult Result, const TCHAR* What);

private:
	HearthWorld* World = nullptr;
	HearthConversion::FixedStepAccumulator Accumulator{1.0 / 60.0, 8};
	// Parallel arrays, one entry per driven body (swap-removed).
	TArray<TWeakObjectPtr<UHearthBodyComponent>> Components;
	TArray<HearthBodyId> Bodies;
	TArray<HearthTransform> Previous; // state before the last step
	TArray<HearthTransform> Current;  // state after the last step
};
