// NOT COMPILED in the Hearth repository (no Unreal Engine there); see ../../../README.md.
#include "HearthMovingPlatform.h"

#include "Components/StaticMeshComponent.h"
#include "Engine/StaticMesh.h"
#include "HearthBodyComponent.h"
#include "UObject/ConstructorHelpers.h"

AHearthMovingPlatform::AHearthMovingPlatform()
{
	PrimaryActorTick.bCanEverTick = true;

	Mesh = CreateDefaultSubobject<UStaticMeshComponent>(TEXT("Mesh"));
	RootComponent = Mesh;
	static ConstructorHelpers::FObjectFinder<UStaticMesh> Cube(TEXT("/Engine/BasicShapes/Cube.Cube"));
	if (Cube.Succeeded())
	{
		Mesh->SetStaticMesh(Cube.Object); // 100 cm cube with one box collision element
	}
	Mesh->SetRelativeScale3D(FVector(4.0, 4.0, 0.2));
	Mesh->SetSimulatePhysics(false);
	Mesh->SetMobility(EComponentMobility::Movable);

	Body = CreateDefaultSubobject<UHearthBodyComponent>(TEXT("HearthBody"));
	Body->BodyType = EHearthBodyType::Kinematic;
}

void AHearthMovingPlatform::BeginPlay()
{
	Super::BeginPlay();
	StartLocation = GetActorLocation();
	StartRotation = GetActorRotation();
	Elapsed = 0.0;
}

void AHearthMovingPlatform::Tick(float DeltaSeconds)
{
	Super::Tick(DeltaSeconds);
	if (!bMoving)
	{
		return; // the body stops with the actor
	}
	Elapsed += DeltaSeconds;
	// 0 -> 1 -> 0 over a cycle, eased (a cosine), so the platform starts and stops gently.
	constexpr double TwoPi = 6.283185307179586;
	const double Phase = TwoPi * Elapsed / FMath::Max(0.1, static_cast<double>(CycleSeconds));
	const double Along = 0.5 - 0.5 * FMath::Cos(Phase);
	const FRotator Rotation = StartRotation + FRotator(0.0, YawDegreesPerSecond * Elapsed, 0.0);
	// Moving the actor is all it takes: the kinematic Hearth body follows it (and pushes what
	// it touches) in UHearthWorldSubsystem's next steps.
	SetActorLocationAndRotation(StartLocation + TravelOffset * Along, Rotation);
}
