// HearthPhysics.Build.cs - links the prebuilt Hearth library and adds its include path.
// NOT COMPILED in the Hearth repository (no Unreal Engine there); see ../../README.md.
//
// Expected layout (bindings/packaging/install.sh --prefix <Plugin>/Source/ThirdParty/hearth):
//   Source/ThirdParty/hearth/include/hearth.h, hearth.hpp
//   Source/ThirdParty/hearth/lib/libhearth.so            (Linux)
//   Source/ThirdParty/hearth/lib/Win64/hearth.dll, hearth.dll.lib   (Win64, copied by hand)
using System.IO;
using UnrealBuildTool;

public class HearthPhysics : ModuleRules
{
	public HearthPhysics(ReadOnlyTargetRules Target) : base(Target)
	{
		PCHUsage = PCHUsageMode.UseExplicitOrSharedPCHs;
		PublicDependencyModuleNames.AddRange(new string[] { "Core", "CoreUObject", "Engine" });

		string HearthRoot = Path.GetFullPath(Path.Combine(ModuleDirectory, "..", "ThirdParty", "hearth"));
		PublicIncludePaths.Add(Path.Combine(HearthRoot, "include"));
		// hearth.hpp's nothrow API works with Unreal's default of no C++ exceptions.
		PublicDefinitions.Add("HEARTH_CPP_NO_EXCEPTIONS=1");

		if (Target.Platform == UnrealTargetPlatform.Linux)
		{
			string Lib = Path.Combine(HearthRoot, "lib", "libhearth.so");
			PublicAdditionalLibraries.Add(Lib);
			// Staged next to the binary; the library has no SONAME, so it is found by file name.
			RuntimeDependencies.Add("$(TargetOutputDir)/libhearth.so", Lib);
		}
		else if (Target.Platform == UnrealTargetPlatform.Win64)
		{
			string LibDir = Path.Combine(HearthRoot, "lib", "Win64");
			PublicAdditionalLibraries.Add(Path.Combine(LibDir, "hearth.dll.lib"));
			PublicDelayLoadDLLs.Add("hearth.dll");
			RuntimeDependencies.Add("$(TargetOutputDir)/hearth.dll", Path.Combine(LibDir, "hearth.dll"));
		}
	}
}
