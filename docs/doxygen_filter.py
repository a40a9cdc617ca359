#!/usr/bin/env python3
"""Doxygen input filter for include/hearth.h: puts every documented item in its group.

The header's comments come from the Rust sources (cbindgen copies each `///` comment), and
stay free of Doxygen commands. This filter adds `\\ingroup <group>` to each top-level doc
comment, chosen from the name of the item that follows it by the naming convention of the
C API (`hearth_<object>_<verb>`, `Hearth<Object>...`, `HEARTH_<OBJECT>_...`). Line numbers
are kept (the command goes on the comment's last line), so Doxygen's warnings point into the
real header.

    docs/doxygen_filter.py include/hearth.h            # the filtered header on stdout (INPUT_FILTER)
    docs/doxygen_filter.py --check include/hearth.h    # lists items no rule places; exit 1 if any

A new kind of object needs a rule in RULES and a \\defgroup in docs/reference.dox; until then
its items go to the group `ungrouped`, which does not exist, so Doxygen warns and the
documentation build (.ci/docs, warnings are errors) fails, and so does `--check`
(tests/docs.rs).
"""

import re
import sys

# (group, pattern) in order: the first match wins.
RULES = [
    ("errors", r"^(hearth_version|hearth_result_name|hearth_last_error_message|HearthResult|HEARTH_OK|HEARTH_ERROR_\w+)$"),
    ("basics", r"^(HEARTH_VERSION\w*|HearthVec3|HearthQuat|HearthTransform)$"),
    ("particle", r"^(hearth_particle_\w+|hearth_burst_\w+|HearthParticle\w*|HearthBurst\w*|HearthExpiredParticle"
                 r"|hearth_world_(get_particle\w*|get_expired_particles|set_particle\w*))$"),
    ("soft_body", r"^(hearth_soft_body_\w+|HearthSoftBody\w*|hearth_world_get_soft_body\w*|HEARTH_SOFT\w*)$"),
    ("joint", r"^(hearth_joint_\w+|hearth_\w+_joint_def_default|Hearth\w*Joint\w*|HEARTH_JOINT_\w+"
              r"|hearth_world_get_broken_joints)$"),
    ("generator", r"^(hearth_generator_\w+|hearth_\w+_generator_def_default|Hearth\w*Generator\w*|HEARTH_GENERATOR_\w+"
                  r"|hearth_contact_sink_\w+|HearthContactSink|HearthGeneratedContact|Hearth(Force|Contact)Callback"
                  r"|HearthLinkEnd|HEARTH_LINK_\w+)$"),
    ("recording", r"^(hearth_record_\w+|hearth_world_record_\w+|HearthRecord\w*)$"),
    ("events", r"^(hearth_world_(get_contact_events|get_sensor_events|get_body_events|set_pair_filter_callback"
               r"|set_pre_solve_callback)|HearthContact(Hit)?Events?|HearthSensorEvents?|HearthBody(Move)?Events?"
               r"|HearthManifoldPoint|HearthPreSolve\w*|HearthPairFilterCallback)$"),
    ("snapshot", r"^(hearth_world_snapshot_\w+|hearth_world_get_user_generators_missing_callback"
                 r"|hearth_generator_set_user_(force|contact)_callback)$"),
    ("geometry", r"^(hearth_hull_\w+|hearth_mesh_\w+|hearth_heightfield_\w+|HearthHull\w*|HearthMesh\w*"
                 r"|HearthHeightfield\w*|HEARTH_MAX_(HULL|MESH|HEIGHTFIELD)_\w+"
                 r"|hearth_shape_create_(hull|mesh|heightfield))$"),
    ("query", r"^(hearth_world_(cast|overlap)_\w+|hearth_query_\w+|hearth_filter_default|hearth_shape_(set|get)_filter"
              r"|HearthQuery\w*|HearthRay\w*|HearthFilter|HEARTH_QUERY_\w+)$"),
    ("shape", r"^(hearth_shape_\w+|HearthShape\w*|HearthSphere|HearthBox|HearthCapsule|HearthPlane)$"),
    ("body", r"^(hearth_body_\w+|HearthBody\w*|HearthMassData|HEARTH_BODY_\w+|HEARTH_LOCK_\w+)$"),
    ("draw", r"^(hearth_world_draw|hearth_debug_draw_default|HearthDebugDraw|HearthDraw\w+)$"),
    ("world", r"^(hearth_world_\w+|HearthWorld\w*|HEARTH_INTEGRATOR_\w+|Hearth(Task|EnqueueTask|FinishTask)Fn)$"),
]
COMPILED = [(group, re.compile(pattern)) for group, pattern in RULES]

# The name an item declares, from its first line.
DECLARATIONS = [
    re.compile(r"^#define\s+(\w+)"),
    re.compile(r"^typedef\s+[^(]*\(\s*\*\s*(\w+)\s*\)"),  # a function pointer type
    re.compile(r"^typedef\s+(?:struct|enum|union)\s+(\w+)"),
    re.compile(r"^(?!typedef)[A-Za-z_][\w\s\*]*?\b(\w+)\s*\("),  # a function: the name before "("
    re.compile(r"^(?:struct|enum|union)\s+(\w+)"),
    re.compile(r"^(\w+),?\s*$"),  # an enum member, indented
]


def group_of(name):
    for group, pattern in COMPILED:
        if pattern.match(name):
            return group
    return None


def declared_name(line):
    text = line.strip()
    for pattern in DECLARATIONS:
        m = pattern.match(text)
        if m:
            return m.group(1)
    return None


def next_code_line(lines, start):
    for j in range(start, len(lines)):
        if lines[j].strip():
            return lines[j]
    return ""


def filter_header(lines):
    """Yields the lines with `\\ingroup` added to every top-level doc comment; collects the
    names no rule places in `filter_header.ungrouped`."""
    out = list(lines)
    ungrouped = []
    i = 0
    while i < len(lines):
        line = lines[i]
        if line.startswith("/**"):
            end = i
            while "*/" not in lines[end]:
                end += 1
            name = declared_name(next_code_line(lines, end + 1))
            if name is not None and name != "HEARTH_H":
                group = group_of(name)
                if group is None:
                    ungrouped.append(name)
                    group = "ungrouped"
                closing = out[end]
                cut = closing.rindex("*/")
                out[end] = closing[:cut].rstrip() + " \\ingroup " + group + " */" + closing[cut + 2:]
            i = end + 1
        else:
            i += 1
    filter_header.ungrouped = ungrouped
    return out


def main(argv):
    check = "--check" in argv
    paths = [a for a in argv[1:] if a != "--check"]
    if len(paths) != 1:
        sys.stderr.write(__doc__)
        return 2
    with open(paths[0], encoding="utf-8") as f:
        lines = f.read().split("\n")
    filtered = filter_header(lines)
    if check:
        if filter_header.ungrouped:
            print("items of include/hearth.h in no documentation group (add a rule to docs/doxygen_filter.py "
                  "and a \\defgroup to docs/reference.dox):")
            for name in filter_header.ungrouped:
                print("  " + name)
            return 1
        return 0
    sys.stdout.write("\n".join(filtered))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
