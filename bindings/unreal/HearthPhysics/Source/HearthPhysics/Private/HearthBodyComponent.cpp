// NOT COMPILED in the Hearth repository; see ../../../README.md.
#include "HearthBodyComponent.h"
#include "HearthConversion.h"
#include "HearthWorldSubsystem.h"
#include "Components/BoxComponent.h"
#include "Components/CapsuleComponent.h"
#include "Components/SphereComponent.h"
#include "Engine/World.h"
#include "GameFramework/Actor.h"

namespace HC = HearthConversion;

void UHearthBodyComponent::BeginPlay()
{
	Super::BeginPlay();
	UHearthWorldSubsystem* Physics = GetWorld()->GetSubsystem<UHearthWorldSubsystem>();
	UPrimitiveComponent* Primitive = Cast<UPrimitiveComponent>(GetOwner()->GetRootComponent());
	if (!Physics || !Physics->GetHearthWorld() || !Primitive)
	{
		return;
	}
	HearthWorld* World = Physics->GetHearthWorld();

	HearthBodyDef Def = hearth_body_def_default();
	Def.type = bDynamic ? HEARTH_BODY_DYNAMIC : HEARTH_BODY_STATIC;
	Def.transform = HC::ToHearthTransform(Primitive->GetComponentLocation(), Primitive->GetComponentQuat());
	Body = Physics->AddBody(this, Def);
	if (Body.generation == 0)
	{
		return;
	}

	HearthShapeDef Material = hearth_shape_def_default();
	Material.density = HC::ToHearthDensity(Density);
	Material.static_friction = Material.dynamic_friction = Friction;
	Material.restitution = Restitution;
	// Shapes in the body frame; the component's scale is baked into their sizes.
	const FVector Scale = Primitive->GetComponentScale().GetAbs();
	HearthShapeId Shape{0, 0};
	HearthResult Result;
	if (const USphereComponent* Sphere = Cast<USphereComponent>(Primitive))
	{
		const HearthSphere S{{0.0f, 0.0f, 0.0f}, static_cast<float>(Sphere->GetUnscaledSphereRadius() * Scale.GetMax() * HC::MetresPerCentimetre)};
		Result = hearth_shape_create_sphere(World, Body, &Material, &S, &Shape);
	}
	else if (const UCapsuleComponent* Capsule = Cast<UCapsuleComponent>(Primitive))
	{
		// Unreal capsules lie along local Z, which is Hearth's local Y.
		const double Radius = Capsule->GetUnscaledCapsuleRadius() * FMath::Max(Scale.X, Scale.Y);
		const double HalfSegment = FMath::Max(0.0, Capsule->GetUnscaledCapsuleHalfHeight() * Scale.Z - Radius);
		const HearthCapsule C{HC::ToHearthVector(FVector(0, 0, -HalfSegment)), HC::ToHearthVector(FVector(0, 0, HalfSegment)),
			static_cast<float>(Radius * HC::MetresPerCentimetre)};
		Result = hearth_shape_create_capsule(World, Body, &Material, &C, &Shape);
	}
	else
	{
		// A box component's extent, or any primitive's local bounding box.
		const UBoxComponent* BoxComponent = Cast<UBoxComponent>(Primitive);
		const FBoxSphereBounds Local = Primitive->CalcBounds(FTransform::Identity);
		const FVector Extent = (BoxComponent ? BoxComponent->GetUnscaledBoxExtent() : Local.BoxExtent) * Scale;
		const FVector Center = BoxComponent ? FVector::ZeroVector : Local.Origin * Scale;
		const HearthBox B{HC::ToHearthVector(Center), {0.0f, 0.0f, 0.0f, 1.0f}, HC::ToHearthVector(Extent)};
		Result = hearth_shape_create_box(World, Body, &Material, &B, &Shape);
	}
	UHearthWorldSubsystem::Check(Result, TEXT("hearth_shape_create"));
}

void UHearthBodyComponent::EndPlay(const EEndPlayReason::Type Reason)
{
	if (UHearthWorldSubsystem* Physics = GetWorld()->GetSubsystem<UHearthWorldSubsystem>())
	{
		Physics->RemoveBody(this);
	}
	Body = HearthBodyId{0, 0};
	Super::EndPlay(Reason);
}

void UHearthBodyComponent::ApplyHearthPose(const FVector& Location, const FQuat& Rotation)
{
	if (bDynamic)
	{
		GetOwner()->SetActorLocationAndRotation(Location, Rotation, false, nullptr, ETeleportType::TeleportPhysics);
	}
}

void UHearthBodyComponent::AddForce(FVector Force)
{
	if (UHearthWorldSubsystem* Physics = GetWorld()->GetSubsystem<UHearthWorldSubsystem>())
	{
		UHearthWorldSubsystem::Check(hearth_body_apply_force(Physics->GetHearthWorld(), Body, HC::ToHearthForce(Force)),
			TEXT("hearth_body_apply_force"));
	}
}

FVector UHearthBodyComponent::GetLinearVelocity() const
{
	HearthVec3 V{0.0f, 0.0f, 0.0f};
	if (UHearthWorldSubsystem* Physics = GetWorld()->GetSubsystem<UHearthWorldSubsystem>())
	{
		hearth_body_get_linear_velocity(Physics->GetHearthWorld(), Body, &V);
	}
	return HC::ToUnrealVector<FVector>(V);
}
