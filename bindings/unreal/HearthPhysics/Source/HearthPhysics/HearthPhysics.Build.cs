// HearthPhysics.Build.cs - links the prebuilt Hearth library and adds its include path.
// NOT COMPILED in the Hearth repository (no Unreal Engine there); see ../../README.md.
//
// Layout (../../README.md, "Installing"):
//   Source/ThirdParty/hearth/include/hearth.h, hearth.hpp
//   Source/ThirdParty/hearth/lib/libhearth.so, libhearth.so.0.2, libhearth.so.0.2.0   (Linux)
//   Source/ThirdParty/hearth/lib/Win64/hearth.dll, hearth.dll.lib                      (Win64)
using System.IO;
using UnrealBuildTool;

public class HearthPhysics : ModuleRules
{
	public HearthPhysics(ReadOnlyTargetRules Target) : base(Target)
	{
		PCHUsage = PCHUsageMode.UseExplicitOrSharedPCHs;
		PublicDependencyModuleNames.AddRange(new string[] { "Core", "CoreUObject", "Engine" });
		// PhysicsCore: FKAggregateGeom (the simple-collision elements), FTriMeshCollisionData;
		// Landscape: ALandscapeProxy and its heightfield collision components; Projects:
		// IPluginManager.
		PrivateDependencyModuleNames.AddRange(new string[] { "PhysicsCore", "Landscape", "Projects" });

		string HearthRoot = Path.Combine(PluginDirectory, "Source", "ThirdParty", "hearth");
		PublicIncludePaths.Add(Path.Combine(HearthRoot, "include"));
		// hearth.hpp's nothrow API works with Unreal's default of no C++ exceptions.
		PublicDefinitions.Add("HEARTH_CPP_NO_EXCEPTIONS=1");

		if (Target.Platform == UnrealTargetPlatform.Linux)
		{
			string LibDir = Path.Combine(HearthRoot, "lib");
			PublicAdditionalLibraries.Add(Path.Combine(LibDir, "libhearth.so"));
			PublicRuntimeLibraryPaths.Add(LibDir);
			// The executable asks for the library's SONAME (libhearth.so.0.2 while the version is
			// 0.2.x): stage every libhearth.so.* file install.sh laid out, next to the rpath.
			foreach (string Versioned in Directory.GetFiles(LibDir, "libhearth.so.*"))
			{
				RuntimeDependencies.Add(Versioned);
			}
		}
		else if (Target.Platform == UnrealTargetPlatform.Win64)
		{
			string LibDir = Path.Combine(HearthRoot, "lib", "Win64");
			PublicAdditionalLibraries.Add(Path.Combine(LibDir, "hearth.dll.lib"));
			// Delay-loaded: FHearthPhysicsModule::StartupModule loads it from the plug-in's
			// Binaries folder before the first hearth_* call (the engine would not look there).
			PublicDelayLoadDLLs.Add("hearth.dll");
			RuntimeDependencies.Add("$(PluginDir)/Binaries/ThirdParty/hearth/Win64/hearth.dll",
				Path.Combine(LibDir, "hearth.dll"));
		}
	}
}
