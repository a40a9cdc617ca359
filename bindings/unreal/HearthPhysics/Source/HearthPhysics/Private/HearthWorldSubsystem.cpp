// NOT COMPILED in the Hearth repository (no Unreal Engine there); see ../../../README.md.
#include "HearthWorldSubsystem.h"

#include "Engine/Engine.h"
#include "Engine/World.h"
#include "HearthBodyComponent.h"
#include "HearthConversion.h"
#include "HearthPhysicsModule.h"
#include "Async/ParallelFor.h"
#include "Async/TaskGraphInterfaces.h"

namespace HC = HearthConversion;

void UHearthWorldSubsystem::LogError(void* /*UserData*/, const char* Message)
{
	UE_LOG(LogHearth, Error, TEXT("%s"), UTF8_TO_TCHAR(Message));
}

void* UHearthWorldSubsystem::EnqueueTask(HearthTaskFn Task, uint32 ItemCount, uint32 MinRange, void* TaskContext, void* UserContext)
{
	const uint32 Workers = static_cast<uint32>(reinterpret_cast<UPTRINT>(UserContext));
	const uint32 MaxChunks = ItemCount / FMath::Max<uint32>(MinRange, 1);
	const uint32 Chunks = FMath::Clamp<uint32>(MaxChunks, 1, Workers);
	const uint32 PerChunk = (ItemCount + Chunks - 1) / Chunks;
	// Every index is covered once; two chunks running at once have distinct indices, all below
	// the world's worker count. Hearth's results do not depend on how the work is cut.
	ParallelFor(static_cast<int32>(Chunks), [=](int32 Chunk)
	{
		const uint32 Start = static_cast<uint32>(Chunk) * PerChunk;
		const uint32 End = FMath::Min(Start + PerChunk, ItemCount);
		if (Start < End)
		{
			Task(Start, End, static_cast<uint32>(Chunk), TaskContext);
		}
	});
	return nullptr; // done: Hearth calls no FinishTask
}

void UHearthWorldSubsystem::FinishTask(void* /*UserTask*/, void* /*UserContext*/)
{
}

uint64 UHearthWorldSubsystem::GetStateHash() const
{
	uint64 Hash = 0;
	HearthWorld* World = Simulation.GetWorld();
	return World && hearth_world_get_hash(World, &Hash) == HEARTH_OK ? Hash : 0;
}

bool UHearthWorldSubsystem::DoesSupportWorldType(const EWorldType::Type WorldType) const
{
	return WorldType == EWorldType::Game || WorldType == EWorldType::PIE;
}

UHearthWorldSubsystem* UHearthWorldSubsystem::GetHearthSubsystem(const UObject* WorldContextObject)
{
	const UWorld* World = GEngine ? GEngine->GetWorldFromContextObject(WorldContextObject, EGetWorldErrorMode::ReturnNull) : nullptr;
	return World ? World->GetSubsystem<UHearthWorldSubsystem>() : nullptr;
}

void UHearthWorldSubsystem::Initialize(FSubsystemCollectionBase& Collection)
{
	Super::Initialize(Collection);
	if (!FHearthPhysicsModule::IsLibraryReady())
	{
		return; // the module logged why
	}
	Simulation.SetErrorCallback(&UHearthWorldSubsystem::LogError, nullptr);
	HearthWorldDef Def = hearth_world_def_default();
	Def.gravity = HC::ToHearthVector(FVector(0.0, 0.0, GetWorld()->GetGravityZ()));
	// Step on Unreal's task graph: its workers plus the game thread, within Hearth's 1..=64.
	const uint32 Workers = static_cast<uint32>(FMath::Clamp(FTaskGraphInterface::Get().GetNumWorkerThreads() + 1, 1, 64));
	Def.worker_count = Workers;
	Def.enqueue_task = &UHearthWorldSubsystem::EnqueueTask;
	Def.finish_task = &UHearthWorldSubsystem::FinishTask;
	Def.user_task_context = reinterpret_cast<void*>(static_cast<UPTRINT>(Workers));
	HearthCore::FSimulationSettings Settings;
	Settings.StepSeconds = StepSeconds;
	Settings.MaxStepsPerFrame = MaxStepsPerFrame;
	Simulation.Create(Def, Settings); // a failure is logged through LogError
}

void UHearthWorldSubsystem::Deinitialize()
{
	Simulation.Destroy();
	Components.Reset();
	Super::Deinitialize();
}

TStatId UHearthWorldSubsystem::GetStatId() const
{
	RETURN_QUICK_DECLARE_CYCLE_STAT(UHearthWorldSubsystem, STATGROUP_Tickables);
}

HearthBodyId UHearthWorldSubsystem::AddBody(UHearthBodyComponent* Component, const HearthBodyDef& Def)
{
	if (!Simulation.IsRunning())
	{
		return HearthBodyId{0, 0};
	}
	const HearthBodyId Body = Simulation.AddBody(Def);
	if (Body.generation != 0)
	{
		Components.AddUnique(Component);
	}
	return Body;
}

void UHearthWorldSubsystem::RemoveBody(UHearthBodyComponent* Component, HearthBodyId Body)
{
	Components.Remove(Component);
	Simulation.RemoveBody(Body);
}

void UHearthWorldSubsystem::Tick(float DeltaTime)
{
	Super::Tick(DeltaTime);
	if (!Simulation.IsRunning())
	{
		return;
	}
	// Gravity is followed every frame (a game mode or a level script may change it).
	Simulation.SetGravity(HC::ToHearthVector(FVector(0.0, 0.0, GetWorld()->GetGravityZ())));
	// Actor ticks ran before this one (tickable objects tick after the tick groups): push what
	// gameplay did to the actors, step, then show the interpolated poses.
	Components.RemoveAll([](const TWeakObjectPtr<UHearthBodyComponent>& Weak) { return !Weak.IsValid(); });
	for (const TWeakObjectPtr<UHearthBodyComponent>& Weak : Components)
	{
		Weak->PushToHearth(Simulation);
	}
	Simulation.Advance(DeltaTime);
	for (const TWeakObjectPtr<UHearthBodyComponent>& Weak : Components)
	{
		Weak->PullFromHearth(Simulation);
	}
}
