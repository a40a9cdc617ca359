// NOT COMPILED in the Hearth repository; see ../../../README.md.
#include "HearthWorldSubsystem.h"
#include "HearthBodyComponent.h"
#include "Engine/World.h"

namespace HC = HearthConversion;

bool UHearthWorldSubsystem::Check(HearthResult Result, const TCHAR* What)
{
	if (Result == HEARTH_OK)
	{
		return true;
	}
	char Message[256];
	hearth_last_error_message(Message, sizeof(Message));
	UE_LOG(LogTemp, Error, TEXT("Hearth: %s failed: %s (%s)"), What, UTF8_TO_TCHAR(hearth_result_name(Result)),
		UTF8_TO_TCHAR(Message));
	return false;
}

bool UHearthWorldSubsystem::DoesSupportWorldType(const EWorldType::Type WorldType) const
{
	return WorldType == EWorldType::Game || WorldType == EWorldType::PIE;
}

void UHearthWorldSubsystem::Initialize(FSubsystemCollectionBase& Collection)
{
	Super::Initialize(Collection);
	if (hearth_version() != HEARTH_VERSION)
	{
		UE_LOG(LogTemp, Error, TEXT("Hearth: library version differs from the header's"));
		return;
	}
	HearthWorldDef Def = hearth_world_def_default();
	// Unreal's gravity (cm/s² along Z) in Hearth terms.
	Def.gravity = HC::ToHearthVector(FVector(0.0, 0.0, GetWorld()->GetGravityZ()));
	Check(hearth_world_create(&Def, &World), TEXT("hearth_world_create"));
}

void UHearthWorldSubsystem::Deinitialize()
{
	hearth_world_destroy(World); // NULL is a no-op
	World = nullptr;
	Components.Reset();
	Bodies.Reset();
	Previous.Reset();
	Current.Reset();
	Super::Deinitialize();
}

TStatId UHearthWorldSubsystem::GetStatId() const
{
	RETURN_QUICK_DECLARE_CYCLE_STAT(UHearthWorldSubsystem, STATGROUP_Tickables);
}

HearthBodyId UHearthWorldSubsystem::AddBody(UHearthBodyComponent* Component, const HearthBodyDef& Def)
{
	HearthBodyId Body{0, 0};
	if (World && Check(hearth_body_create(World, &Def, &Body), TEXT("hearth_body_create")))
	{
		Components.Add(Component);
		Bodies.Add(Body);
		Previous.Add(Def.transform);
		Current.Add(Def.transform);
	}
	return Body;
}

void UHearthWorldSubsystem::RemoveBody(UHearthBodyComponent* Component)
{
	const int32 Index = Components.IndexOfByKey(Component);
	if (Index == INDEX_NONE)
	{
		return;
	}
	Check(hearth_body_destroy(World, Bodies[Index]), TEXT("hearth_body_destroy"));
	Components.RemoveAtSwap(Index);
	Bodies.RemoveAtSwap(Index);
	Previous.RemoveAtSwap(Index);
	Current.RemoveAtSwap(Index);
}

void UHearthWorldSubsystem::Tick(float DeltaTime)
{
	Super::Tick(DeltaTime);
	if (!World)
	{
		return;
	}
	const int32 Steps = Accumulator.Advance(DeltaTime);
	for (int32 Step = 0; Step < Steps; ++Step)
	{
		Previous = Current;
		if (!Check(hearth_world_step(World, static_cast<float>(Accumulator.GetStepSeconds())), TEXT("hearth_world_step")) ||
			!Check(hearth_world_get_transforms(World, Bodies.GetData(), Bodies.Num(), Current.GetData()),
				TEXT("hearth_world_get_transforms")))
		{
			return;
		}
	}
	// Draw every body between its last two physics states.
	const double Alpha = Accumulator.Alpha();
	for (int32 i = 0; i < Components.Num(); ++i)
	{
		if (UHearthBodyComponent* Component = Components[i].Get())
		{
			const HearthTransform Pose = HC::Interpolate(Previous[i], Current[i], Alpha);
			Component->ApplyHearthPose(HC::ToUnrealVector<FVector>(Pose.position), HC::ToUnrealQuat<FQuat>(Pose.rotation));
		}
	}
}
