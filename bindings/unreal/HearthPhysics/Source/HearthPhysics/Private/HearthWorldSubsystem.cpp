// NOT COMPILED in the Hearth repository (no Unreal Engine there); see ../../../README.md.
#include "HearthWorldSubsystem.h"

#include "Engine/Engine.h"
#include "Engine/World.h"
#include "HearthBodyComponent.h"
#include "HearthConversion.h"
#include "HearthPhysicsModule.h"

namespace HC = HearthConversion;

void UHearthWorldSubsystem::LogError(void* /*UserData*/, const char* Message)
{
	UE_LOG(LogHearth, Error, TEXT("%s"), UTF8_TO_TCHAR(Message));
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
