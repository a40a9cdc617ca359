// NOT COMPILED in the Hearth repository (no Unreal Engine there); see ../../../README.md.
#include "HearthPhysicsModule.h"

#include "HAL/PlatformProcess.h"
#include "HearthSimulation.h"
#include "Interfaces/IPluginManager.h"
#include "Misc/Paths.h"
#include "Modules/ModuleManager.h"
#include "hearth.h"

DEFINE_LOG_CATEGORY(LogHearth);

bool FHearthPhysicsModule::bLibraryReady = false;

void FHearthPhysicsModule::StartupModule()
{
	bLibraryReady = false;
#if PLATFORM_WINDOWS
	// hearth.dll is delay-loaded (HearthPhysics.Build.cs) and staged in the plug-in's Binaries
	// folder, where Windows does not look: load it from there before the first hearth_* call.
	const TSharedPtr<IPlugin> Plugin = IPluginManager::Get().FindPlugin(TEXT("HearthPhysics"));
	const FString DllPath = Plugin.IsValid()
		? FPaths::Combine(Plugin->GetBaseDir(), TEXT("Binaries/ThirdParty/hearth/Win64/hearth.dll"))
		: FString();
	DllHandle = DllPath.IsEmpty() ? nullptr : FPlatformProcess::GetDllHandle(*DllPath);
	if (!DllHandle)
	{
		UE_LOG(LogHearth, Error, TEXT("Cannot load %s: Hearth physics is off. Build Hearth for Win64 and copy "
			"hearth.dll and hearth.dll.lib into Source/ThirdParty/hearth/lib/Win64 (see the plug-in README)."),
			DllPath.IsEmpty() ? TEXT("hearth.dll (plug-in HearthPhysics not found)") : *DllPath);
		return;
	}
#endif
	const uint32 LibraryVersion = hearth_version();
	if (!HearthCore::IsCompatibleVersion(LibraryVersion, HEARTH_VERSION))
	{
		UE_LOG(LogHearth, Error, TEXT("The Hearth library is %u.%u.%u but the plug-in was built with hearth.h %u.%u.%u; "
			"use the library and header of one build. Hearth physics is off."),
			LibraryVersion >> 16, (LibraryVersion >> 8) & 0xFF, LibraryVersion & 0xFF,
			HEARTH_VERSION_MAJOR, HEARTH_VERSION_MINOR, HEARTH_VERSION_PATCH);
		return;
	}
	bLibraryReady = true;
	UE_LOG(LogHearth, Log, TEXT("Hearth %u.%u.%u loaded"), LibraryVersion >> 16, (LibraryVersion >> 8) & 0xFF,
		LibraryVersion & 0xFF);
}

void FHearthPhysicsModule::ShutdownModule()
{
	bLibraryReady = false;
	if (DllHandle)
	{
		FPlatformProcess::FreeDllHandle(DllHandle);
		DllHandle = nullptr;
	}
}

bool FHearthPhysicsModule::IsLibraryReady()
{
	return bLibraryReady;
}

IMPLEMENT_MODULE(FHearthPhysicsModule, HearthPhysics)
