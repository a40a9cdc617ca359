// NOT COMPILED in the Hearth repository (no Unreal Engine there); see ../../../README.md.
#include "HearthBodyComponent.h"

#include "Components/PrimitiveComponent.h"
#include "Engine/World.h"
#include "GameFramework/Actor.h"
#include "HearthConversion.h"
#include "HearthPhysicsModule.h"
#include "HearthShapes.h"
#include "HearthSimulation.h"
#include "HearthWorldSubsystem.h"
#include "PhysicsEngine/BodySetup.h"

namespace HC = HearthConversion;

UHearthBodyComponent::UHearthBodyComponent()
{
	PrimaryComponentTick.bCanEverTick = false; // UHearthWorldSubsystem drives it
}

UPrimitiveComponent* UHearthBodyComponent::GetRootPrimitive() const
{
	const AActor* Owner = GetOwner();
	return Owner ? Cast<UPrimitiveComponent>(Owner->GetRootComponent()) : nullptr;
}

HearthCore::FSimulation* UHearthBodyComponent::GetSimulation() const
{
	const UWorld* World = GetWorld();
	UHearthWorldSubsystem* Subsystem = World ? World->GetSubsystem<UHearthWorldSubsystem>() : nullptr;
	return Subsystem && Subsystem->IsSimulating() && HasBody() ? &Subsystem->GetSimulation() : nullptr;
}

void UHearthBodyComponent::BeginPlay()
{
	Super::BeginPlay();
	UHearthWorldSubsystem* Subsystem = GetWorld() ? GetWorld()->GetSubsystem<UHearthWorldSubsystem>() : nullptr;
	UPrimitiveComponent* Primitive = GetRootPrimitive();
	if (!Subsystem || !Subsystem->IsSimulating())
	{
		return; // no library (logged at startup) or not a game world
	}
	if (!Primitive)
	{
		UE_LOG(LogHearth, Warning, TEXT("%s: the actor's root is not a primitive component (static mesh, box, sphere, "
			"capsule); it gets no Hearth body."), *GetNameSafe(GetOwner()));
		return;
	}
	if (Primitive->IsSimulatingPhysics())
	{
		UE_LOG(LogHearth, Warning, TEXT("%s: turning off Unreal's Simulate Physics; Hearth moves this actor."),
			*GetNameSafe(GetOwner()));
		Primitive->SetSimulatePhysics(false);
	}

	HearthBodyDef Def = hearth_body_def_default();
	Def.type = BodyType == EHearthBodyType::Dynamic ? HEARTH_BODY_DYNAMIC
		: (BodyType == EHearthBodyType::Kinematic ? HEARTH_BODY_KINEMATIC : HEARTH_BODY_STATIC);
	Def.transform = HC::ToHearthTransform(Primitive->GetComponentLocation(), Primitive->GetComponentQuat());
	Def.linear_damping = LinearDamping;
	Def.angular_damping = AngularDamping;
	Def.allow_sleep = bAllowSleep ? 1 : 0;
	Body = Subsystem->AddBody(this, Def);
	if (!HasBody())
	{
		return; // logged by the simulation
	}
	if (CreateShapes(Subsystem->GetSimulation(), Primitive) == 0)
	{
		UE_LOG(LogHearth, Error, TEXT("%s: no shape could be made; the body is removed."), *GetNameSafe(GetOwner()));
		Subsystem->RemoveBody(this, Body);
		Body = HearthBodyId{0, 0};
	}
}

int32 UHearthBodyComponent::CreateShapes(HearthCore::FSimulation& Simulation, UPrimitiveComponent* Primitive)
{
	HearthShapeDef Material = hearth_shape_def_default();
	Material.density = HC::ToHearthDensity(Density);
	Material.dynamic_friction = Friction;
	Material.static_friction = FMath::Max(StaticFriction, Friction);
	Material.restitution = Restitution;

	// Shapes live in the body's frame (the component's transform without scale); the scale is
	// baked into them the way Unreal bakes it (HearthShapes.h).
	const FVector Scale = Primitive->GetComponentTransform().GetScale3D();
	int32 Made = 0;
	int32 Unsupported = 0;
	if (const UBodySetup* Setup = Primitive->GetBodySetup())
	{
		const FKAggregateGeom& Geom = Setup->AggGeom;
		for (const FKSphereElem& Elem : Geom.SphereElems)
		{
			HearthSphere Sphere;
			if (HearthShapes::MakeSphere(Elem.Center, Elem.Radius, Scale, Sphere) && Simulation.AddSphere(Body, Material, Sphere))
			{
				++Made;
			}
		}
		for (const FKBoxElem& Elem : Geom.BoxElems)
		{
			HearthBox Box;
			if (HearthShapes::MakeBox(Elem.Center, Elem.Rotation.Quaternion(), Elem.X, Elem.Y, Elem.Z, Scale, Box) &&
				Simulation.AddBox(Body, Material, Box))
			{
				++Made;
			}
		}
		for (const FKSphylElem& Elem : Geom.SphylElems)
		{
			HearthCapsule Capsule;
			if (HearthShapes::MakeCapsule(Elem.Center, Elem.Rotation.Quaternion(), Elem.Radius, Elem.Length, Scale, Capsule) &&
				Simulation.AddCapsule(Body, Material, Capsule))
			{
				++Made;
			}
		}
		// Convex hulls, tapered capsules and level sets have no Hearth shape yet (README).
		Unsupported = Geom.GetElementCount() - Geom.SphereElems.Num() - Geom.BoxElems.Num() - Geom.SphylElems.Num();
	}
	if (Unsupported > 0)
	{
		UE_LOG(LogHearth, Warning, TEXT("%s: %d collision element(s) other than spheres, boxes and capsules have no "
			"Hearth shape yet and are left out."), *GetNameSafe(GetOwner()), Unsupported);
	}
	if (Made == 0)
	{
		// No simple collision at all: the primitive's local bounding box stands in.
		const FBoxSphereBounds Local = Primitive->CalcBounds(FTransform::Identity);
		const FVector Size = Local.BoxExtent * 2.0;
		HearthBox Box;
		if (HearthShapes::MakeBox(Local.Origin, FQuat::Identity, Size.X, Size.Y, Size.Z, Scale, Box) &&
			Simulation.AddBox(Body, Material, Box))
		{
			UE_LOG(LogHearth, Log, TEXT("%s: no simple collision elements; using the bounding box."),
				*GetNameSafe(GetOwner()));
			Made = 1;
		}
	}
	return Made;
}

void UHearthBodyComponent::EndPlay(const EEndPlayReason::Type Reason)
{
	if (HasBody())
	{
		if (UHearthWorldSubsystem* Subsystem = GetWorld() ? GetWorld()->GetSubsystem<UHearthWorldSubsystem>() : nullptr)
		{
			Subsystem->RemoveBody(this, Body);
		}
	}
	Body = HearthBodyId{0, 0};
	Super::EndPlay(Reason);
}

void UHearthBodyComponent::PushToHearth(HearthCore::FSimulation& Simulation)
{
	if (const UPrimitiveComponent* Primitive = HasBody() ? GetRootPrimitive() : nullptr)
	{
		Simulation.SyncFromHost(Body, HC::ToHearthTransform(Primitive->GetComponentLocation(), Primitive->GetComponentQuat()));
	}
}

void UHearthBodyComponent::PullFromHearth(HearthCore::FSimulation& Simulation)
{
	UPrimitiveComponent* Primitive = HasBody() && BodyType == EHearthBodyType::Dynamic ? GetRootPrimitive() : nullptr;
	HearthTransform Pose;
	if (Primitive && Simulation.GetRenderPose(Body, Pose))
	{
		Primitive->SetWorldLocationAndRotation(HC::ToUnrealVector<FVector>(Pose.position),
			HC::ToUnrealQuat<FQuat>(Pose.rotation), false, nullptr, ETeleportType::TeleportPhysics);
	}
}

void UHearthBodyComponent::AddForce(FVector Force)
{
	if (HearthCore::FSimulation* Simulation = GetSimulation())
	{
		Simulation->AddForce(Body, HC::ToHearthForce(Force));
	}
}

void UHearthBodyComponent::AddForceAtLocation(FVector Force, FVector Location)
{
	if (HearthCore::FSimulation* Simulation = GetSimulation())
	{
		Simulation->AddForceAtPoint(Body, HC::ToHearthForce(Force), HC::ToHearthVector(Location));
	}
}

void UHearthBodyComponent::AddTorqueInRadians(FVector Torque)
{
	if (HearthCore::FSimulation* Simulation = GetSimulation())
	{
		Simulation->AddTorque(Body, HC::ToHearthTorque(Torque));
	}
}

void UHearthBodyComponent::AddImpulse(FVector Impulse, bool bVelChange)
{
	if (HearthCore::FSimulation* Simulation = GetSimulation())
	{
		// A velocity change is a velocity (cm/s -> m/s); an impulse converts like a force.
		Simulation->AddImpulse(Body, bVelChange ? HC::ToHearthVector(Impulse) : HC::ToHearthForce(Impulse), bVelChange);
	}
}

void UHearthBodyComponent::AddImpulseAtLocation(FVector Impulse, FVector Location)
{
	if (HearthCore::FSimulation* Simulation = GetSimulation())
	{
		Simulation->AddImpulseAtPoint(Body, HC::ToHearthForce(Impulse), HC::ToHearthVector(Location));
	}
}

void UHearthBodyComponent::AddAngularImpulseInRadians(FVector Impulse)
{
	if (HearthCore::FSimulation* Simulation = GetSimulation())
	{
		Simulation->AddAngularImpulse(Body, HC::ToHearthTorque(Impulse));
	}
}

void UHearthBodyComponent::SetLinearVelocity(FVector Velocity)
{
	if (HearthCore::FSimulation* Simulation = GetSimulation())
	{
		Simulation->SetLinearVelocity(Body, HC::ToHearthVector(Velocity));
	}
}

FVector UHearthBodyComponent::GetLinearVelocity() const
{
	HearthVec3 Velocity{0.0f, 0.0f, 0.0f};
	if (HearthCore::FSimulation* Simulation = GetSimulation())
	{
		Simulation->GetLinearVelocity(Body, Velocity);
	}
	return HC::ToUnrealVector<FVector>(Velocity);
}

void UHearthBodyComponent::SetAngularVelocityInRadians(FVector AngularVelocity)
{
	if (HearthCore::FSimulation* Simulation = GetSimulation())
	{
		Simulation->SetAngularVelocity(Body, HC::ToHearthAngular(AngularVelocity));
	}
}

FVector UHearthBodyComponent::GetAngularVelocityInRadians() const
{
	HearthVec3 AngularVelocity{0.0f, 0.0f, 0.0f};
	if (HearthCore::FSimulation* Simulation = GetSimulation())
	{
		Simulation->GetAngularVelocity(Body, AngularVelocity);
	}
	return HC::ToUnrealAngular<FVector>(AngularVelocity);
}

float UHearthBodyComponent::GetMass() const
{
	float Mass = 0.0f;
	if (HearthCore::FSimulation* Simulation = GetSimulation())
	{
		Simulation->GetMass(Body, Mass);
	}
	return Mass;
}

bool UHearthBodyComponent::IsAwake() const
{
	bool bAwake = false;
	if (HearthCore::FSimulation* Simulation = GetSimulation())
	{
		Simulation->IsAwake(Body, bAwake);
	}
	return bAwake;
}

void UHearthBodyComponent::WakeUp()
{
	if (HearthCore::FSimulation* Simulation = GetSimulation())
	{
		Simulation->SetAwake(Body, true);
	}
}

void UHearthBodyComponent::PutToSleep()
{
	if (HearthCore::FSimulation* Simulation = GetSimulation())
	{
		Simulation->SetAwake(Body, false);
	}
}

void UHearthBodyComponent::TeleportTo(FVector Location, FRotator Rotation)
{
	UPrimitiveComponent* Primitive = GetRootPrimitive();
	if (!Primitive)
	{
		return;
	}
	const FQuat Quat = Rotation.Quaternion();
	Primitive->SetWorldLocationAndRotation(Location, Quat, false, nullptr, ETeleportType::TeleportPhysics);
	if (HearthCore::FSimulation* Simulation = GetSimulation())
	{
		Simulation->Teleport(Body, HC::ToHearthTransform(Location, Quat));
	}
}

void UHearthBodyComponent::MoveKinematic(FVector Location, FRotator Rotation)
{
	if (BodyType != EHearthBodyType::Kinematic)
	{
		if (!bWarnedMoveKinematic) // once: it may be called every frame
		{
			UE_LOG(LogHearth, Warning, TEXT("%s: MoveKinematic on a body that is not kinematic; use TeleportTo."),
				*GetNameSafe(GetOwner()));
			bWarnedMoveKinematic = true;
		}
		return;
	}
	if (UPrimitiveComponent* Primitive = GetRootPrimitive())
	{
		// The body follows the actor in PushToHearth, through the frame's steps.
		Primitive->SetWorldLocationAndRotation(Location, Rotation.Quaternion(), false, nullptr, ETeleportType::None);
	}
}
