// FHearthPhysicsModule - loads the Hearth library at startup and owns the LogHearth category.
// NOT COMPILED in the Hearth repository (no Unreal Engine there); see ../../../README.md.
#pragma once

#include "CoreMinimal.h"
#include "Modules/ModuleInterface.h"

/** Hearth's log category: every message of the plug-in (errors are throttled, see HearthSimulation.h). */
HEARTHPHYSICS_API DECLARE_LOG_CATEGORY_EXTERN(LogHearth, Log, All);

class HEARTHPHYSICS_API FHearthPhysicsModule : public IModuleInterface
{
public:
	virtual void StartupModule() override;
	virtual void ShutdownModule() override;

	/** True once the library is loaded and its version matches the header's ABI (0.minor while
	 * the version is 0.x, then the major): no hearth_* function may be called before. */
	static bool IsLibraryReady();

private:
	void* DllHandle = nullptr;
	static bool bLibraryReady;
};
