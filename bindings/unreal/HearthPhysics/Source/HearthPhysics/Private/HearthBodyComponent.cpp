// NOT COMPILED in the Hearth repository (no Unreal Engine there); see ../../../README.md.
#include "HearthBodyComponent.h"

#include "Components/PrimitiveComponent.h"
#include "Components/StaticMeshComponent.h"
#include "Engine/StaticMesh.h"
#include "Engine/World.h"
#include "GameFramework/Actor.h"
#include "HearthConversion.h"
#include "HearthPhysicsModule.h"
#include "HearthShapes.h"
#include "HearthSimulation.h"
#include "HearthWorldSubsystem.h"
#include "Interfaces/Interface_CollisionDataProvider.h"
#include "LandscapeHeightfieldCollisionComponent.h"
#include "LandscapeProxy.h"
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
	ALandscapeProxy* Landscape = Cast<ALandscapeProxy>(GetOwner());
	if (Landscape)
	{
		BeginPlayLandscape(*Subsystem, Landscape);
		return;
	}
	if (!Primitive)
	{
		UE_LOG(LogHearth, Warning, TEXT("%s: the actor's root is not a primitive component (static mesh, box, sphere, "
			"capsule) nor is the actor a landscape; it gets no Hearth body."), *GetNameSafe(GetOwner()));
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

HearthShapeDef UHearthBodyComponent::MakeMaterial() const
{
	HearthShapeDef Material = hearth_shape_def_default();
	Material.density = HC::ToHearthDensity(Density);
	Material.dynamic_friction = Friction;
	Material.static_friction = FMath::Max(StaticFriction, Friction);
	Material.restitution = Restitution;
	return Material;
}

void UHearthBodyComponent::BeginPlayLandscape(UHearthWorldSubsystem& Subsystem, ALandscapeProxy* Landscape)
{
	if (BodyType == EHearthBodyType::Dynamic)
	{
		UE_LOG(LogHearth, Warning, TEXT("%s: a landscape is level geometry; its Hearth body is made static."),
			*GetNameSafe(Landscape));
	}
	// The body's frame is the landscape actor's transform without its scale; each collision
	// component is a heightfield placed at its offset in that frame.
	HearthBodyDef Def = hearth_body_def_default();
	Def.type = BodyType == EHearthBodyType::Kinematic ? HEARTH_BODY_KINEMATIC : HEARTH_BODY_STATIC;
	Def.transform = HC::ToHearthTransform(Landscape->GetActorLocation(), Landscape->GetActorQuat());
	Body = Subsystem.AddBody(this, Def);
	if (HasBody() && CreateLandscapeShapes(Subsystem.GetSimulation(), Landscape) == 0)
	{
		UE_LOG(LogHearth, Error, TEXT("%s: no heightfield could be made; the body is removed."), *GetNameSafe(Landscape));
		Subsystem.RemoveBody(this, Body);
		Body = HearthBodyId{0, 0};
	}
}

int32 UHearthBodyComponent::CreateLandscapeShapes(HearthCore::FSimulation& Simulation, ALandscapeProxy* Landscape)
{
	const HearthShapeDef Material = MakeMaterial();
	const FTransform Frame(Landscape->GetActorQuat(), Landscape->GetActorLocation());
	int32 Made = 0;
	TArray<float> Heights;
	TArray<uint8> Holes;
	for (ULandscapeHeightfieldCollisionComponent* Collision : Landscape->CollisionComponents)
	{
		if (!Collision)
		{
			continue;
		}
		// Samples every CollisionScale local units (one landscape quad at full resolution) over
		// CollisionSizeQuads quads, heights in local units; the component's scale turns both
		// into cm (HearthShapes::MakeHeightfield). The height of a sample is read through
		// ALandscapeProxy::GetHeightAtLocation (exported; the collision component's own
		// GetHeight is not), at the sample's world position, and taken back into the
		// component's frame. A sample without a height (a visibility hole) makes the cells
		// around it holes.
		const FTransform& ComponentToWorld = Collision->GetComponentTransform();
		const int32 Quads = Collision->CollisionSizeQuads;
		const float Spacing = Collision->CollisionScale;
		const int32 Size = Quads + 1;
		Heights.SetNumZeroed(Size * Size);
		Holes.SetNumZeroed(Quads * Quads);
		bool bAnyHole = false;
		for (int32 Y = 0; Y < Size; ++Y)
		{
			for (int32 X = 0; X < Size; ++X)
			{
				const FVector At = ComponentToWorld.TransformPosition(FVector(X * Spacing, Y * Spacing, 0.0));
				const TOptional<float> Height = Landscape->GetHeightAtLocation(At, EHeightfieldSource::Simple);
				Heights[Y * Size + X] = Height.IsSet()
					? static_cast<float>(ComponentToWorld.InverseTransformPosition(FVector(At.X, At.Y, Height.GetValue())).Z)
					: 0.0f;
				if (!Height.IsSet())
				{
					bAnyHole = true;
					for (int32 CY = FMath::Max(Y - 1, 0); CY <= FMath::Min(Y, Quads - 1); ++CY)
					{
						for (int32 CX = FMath::Max(X - 1, 0); CX <= FMath::Min(X, Quads - 1); ++CX)
						{
							Holes[CY * Quads + CX] = 1;
						}
					}
				}
			}
		}
		const HearthTransform Local = HC::ToHearthTransform(
			Frame.InverseTransformPositionNoScale(ComponentToWorld.GetLocation()),
			Frame.InverseTransformRotation(ComponentToWorld.GetRotation()));
		if (Simulation.AddHeightfield(Body, Material, Collision, static_cast<uint32_t>(Size), static_cast<uint32_t>(Size),
				Heights.GetData(), bAnyHole ? Holes.GetData() : nullptr, Spacing, Spacing, ComponentToWorld.GetScale3D(), Local))
		{
			++Made;
		}
	}
	return Made;
}

bool UHearthBodyComponent::CreateMeshShape(HearthCore::FSimulation& Simulation, UPrimitiveComponent* Primitive,
	const HearthShapeDef& Material)
{
	// The triangles Unreal cooks for complex collision (a static mesh's render LODs; cooked
	// builds need "Allow CPU Access" on the mesh), in component space and Unreal's winding,
	// which HearthShapes::ConvertIndices keeps facing the right way.
	UStaticMeshComponent* MeshComponent = Cast<UStaticMeshComponent>(Primitive);
	UStaticMesh* Mesh = MeshComponent ? MeshComponent->GetStaticMesh() : nullptr;
	FTriMeshCollisionData Data;
	if (!Mesh || !Mesh->ContainsPhysicsTriMeshData(true) || !Mesh->GetPhysicsTriMeshData(&Data, true))
	{
		UE_LOG(LogHearth, Warning, TEXT("%s: no triangle data for complex collision (is Allow CPU Access on?); "
			"using the simple collision."), *GetNameSafe(GetOwner()));
		return false;
	}
	TArray<FVector> Vertices;
	Vertices.Reserve(Data.Vertices.Num());
	for (const FVector3f& Vertex : Data.Vertices)
	{
		Vertices.Add(FVector(Vertex));
	}
	TArray<uint32> Indices;
	Indices.Reserve(Data.Indices.Num() * 3);
	for (const FTriIndices& Triangle : Data.Indices)
	{
		Indices.Add(static_cast<uint32>(Triangle.v0));
		Indices.Add(static_cast<uint32>(Triangle.v1));
		Indices.Add(static_cast<uint32>(Triangle.v2));
	}
	return Simulation.AddMesh(Body, Material, Mesh, Vertices.GetData(), static_cast<size_t>(Vertices.Num()),
		Indices.GetData(), static_cast<size_t>(Indices.Num()), Primitive->GetComponentTransform().GetScale3D());
}

int32 UHearthBodyComponent::CreateShapes(HearthCore::FSimulation& Simulation, UPrimitiveComponent* Primitive)
{
	const HearthShapeDef Material = MakeMaterial();

	// Shapes live in the body's frame (the component's transform without scale); the scale is
	// baked into them the way Unreal bakes it (HearthShapes.h).
	const FVector Scale = Primitive->GetComponentTransform().GetScale3D();
	int32 Made = 0;
	int32 Unsupported = 0;
	const UBodySetup* Setup = Primitive->GetBodySetup();
	const bool bComplex = BodyType != EHearthBodyType::Dynamic && Setup &&
		(bUseComplexCollision || Setup->GetCollisionTraceFlag() == CTF_UseComplexAsSimple);
	if (bComplex && CreateMeshShape(Simulation, Primitive, Material))
	{
		return 1;
	}
	if (Setup)
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
		// Convex elements: one hull per element of the body setup, shared by every component
		// of the same mesh (keyed by the body setup and the element's index). VertexData is
		// in the element's frame; its transform puts it in the component's.
		TArray<FVector> Points;
		for (int32 Index = 0; Index < Geom.ConvexElems.Num(); ++Index)
		{
			const FKConvexElem& Elem = Geom.ConvexElems[Index];
			const FTransform ElemTransform = Elem.GetTransform();
			Points.Reset(Elem.VertexData.Num());
			for (const FVector& Vertex : Elem.VertexData)
			{
				Points.Add(ElemTransform.TransformPosition(Vertex));
			}
			if (Simulation.AddHull(Body, Material, Setup, Index, Points.GetData(), static_cast<size_t>(Points.Num()), Scale))
			{
				++Made;
			}
		}
		// Tapered capsules and level sets have no Hearth shape (README).
		Unsupported = Geom.GetElementCount() - Geom.SphereElems.Num() - Geom.BoxElems.Num() - Geom.SphylElems.Num() -
			Geom.ConvexElems.Num();
	}
	if (Unsupported > 0)
	{
		UE_LOG(LogHearth, Warning, TEXT("%s: %d collision element(s) other than spheres, boxes, capsules and convex "
			"elements have no Hearth shape and are left out."), *GetNameSafe(GetOwner()), Unsupported);
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
