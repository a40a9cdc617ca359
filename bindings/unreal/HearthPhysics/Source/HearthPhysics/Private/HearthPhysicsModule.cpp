// The module itself: nothing to start or stop (worlds belong to UHearthWorldSubsystem).
// NOT COMPILED in the Hearth repository; see ../../../README.md.
#include "Modules/ModuleManager.h"

IMPLEMENT_MODULE(FDefaultModuleImpl, HearthPhysics)
