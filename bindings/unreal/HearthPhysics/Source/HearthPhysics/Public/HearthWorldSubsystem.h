// UHearthWorldSubsystem - one Hearth world per game world, stepped on a fixed time step.
// NOT COMPILED in the Hearth repository (no Unreal Engine there); see ../../../README.md.
//
// Thin glue: the stepping, the force and kinematic semantics, the interpolation, gameplay-move
// detection and error throttling are HearthCore::FSimulation (HearthSimulation.h), and every
// unit and axis conversion is HearthConversion.h; both are compiled and tested in the Hearth
// repository. This class only feeds them Unreal's frame time, gravity and actor poses.
#pragma once

#include "CoreMinimal.h"
#include "HearthSimulation.h"
#include "Subsystems/WorldSubsystem.h"
#include "hearth.h"
#include "HearthWorldSubsystem.generated.h"

class UHearthBodyComponent;

UCLASS()
class HEARTHPHYSICS_API UHearthWorldSubsystem : public UTickableWorldSubsystem
{
	GENERATED_BODY()

public:
	/** The fixed step (s) and the most steps one frame may run (longer frames drop the rest). */
	static constexpr double StepSeconds = 1.0 / 60.0;
	static constexpr int32 MaxStepsPerFrame = 8;

	virtual void Initialize(FSubsystemCollectionBase& Collection) override;
	virtual void Deinitialize() override;
	virtual void Tick(float DeltaTime) override;
	virtual TStatId GetStatId() const override;
	virtual bool DoesSupportWorldType(const EWorldType::Type WorldType) const override;

	/** The subsystem of the world WorldContextObject is in (null outside game worlds). */
	UFUNCTION(BlueprintPure, Category = "Hearth", meta = (WorldContext = "WorldContextObject"))
	static UHearthWorldSubsystem* GetHearthSubsystem(const UObject* WorldContextObject);

	/** Whether the Hearth world exists and steps (false when the library failed to load). */
	UFUNCTION(BlueprintPure, Category = "Hearth")
	bool IsSimulating() const { return Simulation.IsRunning(); }

	/** Bodies driven by Hearth Body components. */
	UFUNCTION(BlueprintPure, Category = "Hearth")
	int32 GetBodyCount() const { return Simulation.GetBodyCount(); }

	/** Fixed steps run since play began. */
	UFUNCTION(BlueprintPure, Category = "Hearth")
	int64 GetStepCount() const { return static_cast<int64>(Simulation.GetStepCount()); }

	/** Registers a component's body (Hearth units, from hearth_body_def_default()). */
	HearthBodyId AddBody(UHearthBodyComponent* Component, const HearthBodyDef& Def);
	/** Destroys the component's body. */
	void RemoveBody(UHearthBodyComponent* Component, HearthBodyId Body);

	HearthCore::FSimulation& GetSimulation() { return Simulation; }

	/** Hearth's world state hash (hearth_world_get_hash): equal for equal runs at any worker
	 *  count, for replays and lockstep checks. 0 when not simulating. */
	uint64 GetStateHash() const;

private:
	/** FSimulation's error callback: LogHearth, already throttled. */
	static void LogError(void* UserData, const char* Message);

	/** Hearth's job-system callbacks on Unreal's task graph (HearthWorldDef::enqueue_task):
	 *  the task is cut into at most the world's worker count of chunks that ParallelFor runs
	 *  and waits for, the chunk index as the worker index, so EnqueueTask returns nullptr
	 *  (already done) and FinishTask is never called. UserContext carries the worker count. */
	static void* EnqueueTask(HearthTaskFn Task, uint32 ItemCount, uint32 MinRange, void* TaskContext, void* UserContext);
	static void FinishTask(void* UserTask, void* UserContext);

	HearthCore::FSimulation Simulation;
	TArray<TWeakObjectPtr<UHearthBodyComponent>> Components;
};
