//! Every documented number is an asserted number.
//!
//! `FIGURES` lists each figure with a unit (a number followed by %, m, mm, s, J, N·m, ...)
//! that README.md, ARCHITECTURE.md, docs/comparison.md or the header's doc comments
//! (`include/hearth.h`, made from `src/capi/*.rs` and `build.rs`) state, with what backs it:
//!
//! * `Measured`: the test(s) asserting it at the stated precision. The test must exist and
//!   its doc comment or body must mention the figure's number (the bound, or a comment
//!   quoting the document next to it), so the two are read side by side.
//! * `Input`: a quantity a test's scene is built with (a mass, a height, a load); the test
//!   must exist.
//! * `Range`: an end of a supported range or a documented limit; `tests/ranges.rs` checks
//!   every limit against the enforced one (`documented_ranges_are_the_enforced_ones`) and
//!   both ends in every subsystem.
//! * `Fact`: arithmetic of f32, asserted in this file (`f32_facts_the_documents_use`).
//! * `Setting`: a default or a design constant of the code, not a claim about its results.
//! * `History`: what an earlier version measured, to say why the code is as it is.
//! * `Bench`: a timing (criterion or callgrind). Wall-clock times are never asserted (the
//!   machine is shared); the README states how and when they were measured.
//!
//! `every_documented_figure_is_listed` fails when a document states a figure that has no
//! entry here (a new claim needs its test), and when an entry's figure is no longer in its
//! document.

use std::collections::BTreeSet;
use std::path::Path;

#[derive(Clone, Copy, Debug)]
enum Backing {
    Measured(&'static [&'static str]),
    Input(&'static str),
    Range,
    Fact,
    Setting(&'static str),
    History(&'static str),
    Bench,
}
use Backing::*;

const R: &str = "README.md";
const A: &str = "ARCHITECTURE.md";
const H: &str = "include/hearth.h";
/// The side-by-side comparison with Rapier (issue 13): every figure in it is a Bench.
const C: &str = "docs/comparison.md";

/// (document, figure as scanned: number, one space, unit; backing). Tests are named
/// `file::function` under `tests/`.
const FIGURES: &[(&str, &str, Backing)] = &[
    // Sleep: the lag after a landing, the motion average's half-life and the seed's.
    (
        R,
        "0.85 s",
        Measured(&[
            "rigid_dynamics::a_landed_box_sleeps_time_to_sleep_after_it_stopped",
            "rigid_dynamics::random_drops_sleep_time_to_sleep_after_they_stop",
        ]),
    ),
    (
        A,
        "0.1 s",
        Setting("the half-life of the sleep motion average (island.rs)"),
    ),
    (A, "1 s", History("the seed's half-life of the sleep motion average")),
    (
        A,
        "3.8 s",
        History("how long after a landing the seed's rule slept (island.rs)"),
    ),
    // Header: the accepted mass override (hearth_body_set_mass_data).
    (H, "1e17 kg", Measured(&["setters::bad_input_changes_nothing"])),
    (H, "1e26 kg·m²", Measured(&["setters::bad_input_changes_nothing"])),
    // Header: debug draw of contacts (HearthDebugDraw.draw_contacts).
    (
        H,
        "0.25 m",
        Measured(&["draw::flags_draw_aabbs_contacts_joints_and_centres_of_mass"]),
    ),
    (
        H,
        "0.1 m",
        Measured(&["draw::flags_draw_aabbs_contacts_joints_and_centres_of_mass"]),
    ),
    // README: the C snippet.
    (
        R,
        "0.50 m",
        Measured(&["docs::readme_and_api_guide_snippets_leave_the_box_on_the_ground"]),
    ),
    // README: supported ranges.
    (
        R,
        "1.7e-18 kg·m²",
        Measured(&["ranges::the_largest_torque_on_the_smallest_body_leaves_it_finite"]),
    ),
    (R, "0.1 s", Range),
    // README: snapshots.
    (R, "56 B/body", Measured(&["snapshot::pile_snapshot_size_per_body"])),
    (R, "68 B/body", Measured(&["snapshot::pile_snapshot_size_per_body"])),
    (R, "1 ms", Range),
    (
        R,
        "2 cm",
        Measured(&[
            "ranges::every_subsystem_runs_at_the_shortest_and_the_longest_step",
            "joint_loops::seeded_random_limited_hinge_and_ball_chains_hold_their_joints",
        ]),
    ),
    (R, "10000 m", Range),
    (
        R,
        "1 mm",
        Measured(&[
            "robustness::a_slider_set_up_45_degrees_off_stays_on_its_axis",
            "joint_loops::slider_crank_puts_its_piston_where_the_crank_angle_says",
            "joint_loops::seeded_random_limited_hinge_and_ball_chains_hold_their_joints",
        ]),
    ),
    // README, joints: random closed loops' energy bound.
    (
        R,
        "15 %",
        Measured(&["joint_loops::seeded_random_rings_of_every_joint_kind_hold_and_gain_no_energy"]),
    ),
    (
        R,
        "3.5 %",
        Measured(&["joint_loops::seeded_random_open_chains_with_limits_and_springs_gain_no_energy"]),
    ),
    // ARCHITECTURE, joints left to Gauss-Seidel: the worst energy rises.
    // ARCHITECTURE and README, open chains with limits in the forest: worst joint errors and
    // energy, and by Gauss-Seidel before.
    (
        A,
        "0.17 %",
        Measured(&["joint_loops::seeded_random_limited_hinge_and_ball_chains_hold_their_joints"]),
    ),
    (
        A,
        "1.1 cm",
        Measured(&["joint_loops::seeded_random_limited_hinge_and_ball_chains_hold_their_joints"]),
    ),
    (
        A,
        "5 mm",
        Measured(&["joint_loops::seeded_random_limited_hinge_and_ball_chains_hold_their_joints"]),
    ),
    (
        A,
        "0.85 m",
        Measured(&["joint_loops::seeded_random_limited_hinge_and_ball_chains_hold_their_joints"]),
    ),
    (
        R,
        "0.85 m",
        Measured(&["joint_loops::seeded_random_limited_hinge_and_ball_chains_hold_their_joints"]),
    ),
    (
        A,
        "32.6 %",
        Measured(&["joint_loops::seeded_random_rings_with_limits_and_springs_gain_no_energy"]),
    ),
    (R, "10 km", Range),
    (R, "100000 m", Range),
    (R, "8 mm", Fact),
    // README, locked axes: the 6-link planar hinge chain's worst separation.
    (
        R,
        "16 mm",
        Measured(&["locked_joints::planar_hinge_chains_swing_in_their_plane_hold_together_and_gain_no_energy"]),
    ),
    (R, "100 km", Fact),
    (R, "10000 m/s", Range),
    (R, "314.16 rad/s", Range),
    (R, "10000 rad/s", Range),
    (R, "10000 m/s²", Range),
    (R, "1e12 N", Range),
    (R, "1e10 N·s", Range),
    (R, "100000 kg/m³", Range),
    (R, "1 µg", Range),
    (R, "1e6 Hz", Range),
    // README: feature status.
    (
        R,
        "0.3 m",
        Input(
            "soft_robustness::a_box_twenty_times_the_ball_s_mass_does_not_get_in_or_push_the_skin_through_the_ground",
        ),
    ),
    (
        R,
        "0.5 %",
        Measured(&[
            "soft::pressurised_icosphere_bounces_settles_and_keeps_its_volume",
            "soft::a_64x64_cloth_pinned_at_two_corners_hangs_without_stretching",
            "joint_loops::parallelogram_linkage_swings_with_its_analytic_period_and_keeps_its_bar_level",
        ]),
    ),
    (
        R,
        "1 %",
        Measured(&[
            "soft_robustness::the_default_skin_stays_within_one_percent_of_its_rest_lengths_up_to_nrt_1600",
            "events::a_dropped_box_gives_one_begin_one_hit_at_the_free_fall_speed_and_an_end_when_lifted",
        ]),
    ),
    (
        R,
        "1,600 J",
        Measured(&["soft_robustness::the_default_skin_stays_within_one_percent_of_its_rest_lengths_up_to_nrt_1600"]),
    ),
    (
        R,
        "20 ×",
        Input(
            "soft_robustness::a_box_twenty_times_the_ball_s_mass_does_not_get_in_or_push_the_skin_through_the_ground",
        ),
    ),
    (
        R,
        "1.5 cm",
        Measured(&[
            "soft_robustness::a_box_twenty_times_the_ball_s_mass_does_not_get_in_or_push_the_skin_through_the_ground",
        ]),
    ),
    (R, "2e-6 m", Measured(&["particles::rods_hold_their_length_under_load"])),
    (R, "10 kg", Input("particles::rods_hold_their_length_under_load")),
    (
        R,
        "40 kg",
        Input("particles::a_rope_bridge_of_particles_carries_a_rigid_box"),
    ),
    (R, "0.001 %", Measured(&["joints::hinge_pendulum_matches_its_period"])),
    (
        R,
        "100 ×",
        Input("joints::heavy_chain_barely_stretches_and_does_not_jitter"),
    ),
    (
        R,
        "0.000 %",
        Measured(&["joints::heavy_chain_barely_stretches_and_does_not_jitter"]),
    ),
    (R, "2000 N·m", Input("joints::hinge_and_slider_limits_hold_under_load")),
    (
        R,
        "2 %",
        Measured(&[
            "robustness::random_setups_stay_finite_bounded_and_do_not_gain_energy",
            "soft::pressurised_icosphere_bounces_settles_and_keeps_its_volume",
            "rigid_dynamics::intermediate_axis_spin_tumbles_and_conserves_momentum",
            "rolling::spinning_ball_and_capsule_stop_in_the_analytic_time",
        ]),
    ),
    (
        R,
        "45 °",
        Input("robustness::a_slider_set_up_45_degrees_off_stays_on_its_axis"),
    ),
    // README, the ragdoll bench (benches/joints.rs): forest and Gauss-Seidel.
    (R, "12 ms/step", Bench),
    (R, "74 ms/step", Bench),
    (R, "2.5 ms/step", Bench),
    (R, "7.9 ms/step", Bench),
    (R, "65 %", Bench),
    (R, "8 %", Bench),
    // README: measured.
    (
        R,
        "5 %",
        Measured(&[
            "rigid_dynamics::bounce_height_is_restitution_squared",
            "queries::stepping_keeps_the_tree_within_five_percent_of_a_full_rebuild",
        ]),
    ),
    (
        R,
        "3 %",
        Measured(&["rigid_dynamics::sliding_distance_uses_dynamic_friction"]),
    ),
    (
        R,
        "20 s",
        Input("rigid_dynamics::intermediate_axis_spin_tumbles_and_conserves_momentum"),
    ),
    (R, "10 s", Input("stacking::tower_of_30_boxes_stands_and_sleeps")),
    (
        R,
        "5 cm",
        Measured(&[
            "stacking::tower_of_30_boxes_stands_and_sleeps",
            "stacking::pyramid_of_385_boxes_stands_and_sleeps",
        ]),
    ),
    (
        R,
        "250 m/s",
        Input("stacking::fast_sphere_does_not_tunnel_through_a_thin_wall"),
    ),
    (
        R,
        "20 cm",
        Input("stacking::fast_sphere_does_not_tunnel_through_a_thin_wall"),
    ),
    (R, "40 %", Bench),
    // The own pool's spin before a worker parks (parallel/pool.rs, SPIN).
    (
        R,
        "50 µs",
        Setting("the own pool's spin before parking (parallel/pool.rs SPIN)"),
    ),
    (
        A,
        "50 µs",
        Setting("the own pool's spin before parking (parallel/pool.rs SPIN)"),
    ),
    // README: threads, perf shares of the parallel stages, their Amdahl bounds and the
    // measured ratios.
    (R, "2.1 ×", Bench),
    (R, "1.9 ×", Bench),
    (R, "1.8 ×", Bench),
    (R, "1.7 ×", Bench),
    (R, "1.4 ×", Bench),
    (R, "1.1 ×", Bench),
    (R, "2 ms", Bench),
    (R, "1.5 ×", Bench),
    (R, "12.0 ms/step", Bench),
    (R, "0.47 ×", Bench),
    (R, "0.71 ×", Bench),
    (R, "0.28 ×", Bench),
    (R, "9.1 M", Bench),
    (R, "39 M", Bench),
    (R, "48 M", Bench),
    (R, "11.1 M", Bench),
    (R, "10.8 M", Bench),
    (R, "2.8 %", Bench),
    (R, "33 M", Bench),
    // docs/comparison.md: Hearth and Rapier side by side on the hull and terrain scenes.
    (C, "257 ×", Bench),
    (C, "71.2 M", Bench),
    (C, "45.1 M", Bench),
    (C, "37 %", Bench),
    (C, "32.5 M", Bench),
    (C, "34.2 M", Bench),
    (C, "0.1 %", Bench),
    (C, "15.5 %", Bench),
    (C, "26.3 M", Bench),
    (C, "21.8 M", Bench),
    (C, "10.5 %", Bench),
    (C, "10.0 %", Bench),
    (C, "37.7 M", Bench),
    (C, "37.0 M", Bench),
    (C, "36.8 M", Bench),
    (C, "36.1 M", Bench),
    (C, "34.9 M", Bench),
    (C, "7.4 %", Bench),
    (C, "12.1 ms", Bench),
    (C, "29.40 M", Bench),
    (C, "26.26 M", Bench),
    (C, "8.8 %", Bench),
    (C, "5.1 %", Bench),
    (C, "3.4 %", Bench),
    (C, "2.7 M", Bench),
    (C, "5 M", Bench),
    (C, "2 M", Bench),
    (C, "4 M", Bench),
    (C, "7.7 ms", Bench),
    (
        C,
        "2 mm",
        Setting("hull_hull's EDGE_ABS_TOL, the slack an edge axis needs over a face"),
    ),
    (C, "1 mm", Setting("the body-pair manifold cache's reuse distance")),
    // docs/comparison.md, Jolt 5.0.0 section: Jolt's settings and the peer's scene set-up
    // (Setting), and the side-by-side measurements on a shared machine (Bench).
    (C, "0.000 m/s", Bench),
    (
        C,
        "0.02 m",
        Setting("the Jolt runner's scene and solver settings (docs/comparison.md, Jolt 5.0.0)"),
    ),
    (
        C,
        "0.03 m/s",
        Setting("the Jolt runner's scene and solver settings (docs/comparison.md, Jolt 5.0.0)"),
    ),
    (
        C,
        "0.05 m",
        Setting("the Jolt runner's scene and solver settings (docs/comparison.md, Jolt 5.0.0)"),
    ),
    (
        C,
        "0.05 m/s",
        Setting("the Jolt runner's scene and solver settings (docs/comparison.md, Jolt 5.0.0)"),
    ),
    (
        C,
        "0.2 m",
        Setting("the Jolt runner's scene and solver settings (docs/comparison.md, Jolt 5.0.0)"),
    ),
    (
        C,
        "0.3 m",
        Setting("the Jolt runner's scene and solver settings (docs/comparison.md, Jolt 5.0.0)"),
    ),
    (
        C,
        "0.5 s",
        Setting("the Jolt runner's scene and solver settings (docs/comparison.md, Jolt 5.0.0)"),
    ),
    (
        C,
        "1 m",
        Setting("the Jolt runner's scene and solver settings (docs/comparison.md, Jolt 5.0.0)"),
    ),
    (C, "1.24 mm", Bench),
    (C, "110 ms/step", Bench),
    (
        C,
        "12 m/s",
        Setting("the Jolt runner's scene and solver settings (docs/comparison.md, Jolt 5.0.0)"),
    ),
    (C, "13 %", Bench),
    (C, "18.8 ms/step", Bench),
    (C, "19 ×", Bench),
    (C, "2 ×", Bench),
    (
        C,
        "256 ×",
        Setting("the Jolt runner's scene and solver settings (docs/comparison.md, Jolt 5.0.0)"),
    ),
    (
        C,
        "400 m",
        Setting("the Jolt runner's scene and solver settings (docs/comparison.md, Jolt 5.0.0)"),
    ),
    (
        C,
        "400 m/s",
        Setting("the Jolt runner's scene and solver settings (docs/comparison.md, Jolt 5.0.0)"),
    ),
    (
        C,
        "400 ×",
        Setting("the Jolt runner's scene and solver settings (docs/comparison.md, Jolt 5.0.0)"),
    ),
    (C, "46.9 ms/step", Bench),
    (
        C,
        "5 °",
        Setting("the Jolt runner's scene and solver settings (docs/comparison.md, Jolt 5.0.0)"),
    ),
    (
        C,
        "500 m/s",
        Setting("the Jolt runner's scene and solver settings (docs/comparison.md, Jolt 5.0.0)"),
    ),
    (C, "7 mm", Bench),
    (
        C,
        "1 °",
        Setting("the body-pair manifold cache's reuse angle, about a degree"),
    ),
    // README: rolling resistance and torsional friction (tests/rolling.rs).
    (
        R,
        "1.5 %",
        Measured(&["rolling::rolling_bodies_stop_after_the_analytic_distance"]),
    ),
    (
        R,
        "5.7 m",
        Measured(&["rolling::rolling_bodies_stop_after_the_analytic_distance"]),
    ),
    (
        R,
        "2 m/s",
        Input("rolling::rolling_bodies_stop_after_the_analytic_distance"),
    ),
    (
        R,
        "1 m",
        Input("rolling::random_rolling_bodies_lose_energy_and_come_to_rest"),
    ),
    (
        R,
        "5 m/s",
        Input("rolling::random_rolling_bodies_lose_energy_and_come_to_rest"),
    ),
    (
        R,
        "5 rad/s",
        Input("rolling::random_rolling_bodies_lose_energy_and_come_to_rest"),
    ),
    (
        R,
        "1.2 ×",
        Measured(&["rolling::random_rolling_bodies_lose_energy_and_come_to_rest"]),
    ),
    (
        R,
        "4.5 s",
        Measured(&["rolling::random_rolling_bodies_lose_energy_and_come_to_rest"]),
    ),
    (R, "16 s", Measured(&["rolling::demo_scene_ends_asleep"])),
    (
        R,
        "30 s",
        Measured(&["bindings_cpp::cpp_pyramid_prints_what_the_c_pyramid_prints"]),
    ),
    (R, "8 s", Measured(&["rolling::ragdoll_comes_to_rest_and_sleeps"])),
    // README: mass ratios and small bodies (tests/mass_ratios.rs).
    (
        R,
        "0.031 mm",
        Measured(&["mass_ratios::heavy_box_on_a_light_box_rests_at_the_closed_form_height"]),
    ),
    (
        R,
        "4.3 mm",
        Measured(&["mass_ratios::hundred_kilograms_on_one_kilogram"]),
    ),
    (R, "100 kg", Input("mass_ratios::hundred_kilograms_on_one_kilogram")),
    (R, "1 kg", Input("mass_ratios::hundred_kilograms_on_one_kilogram")),
    (R, "5 s", Measured(&["mass_ratios::hundred_kilograms_on_one_kilogram"])),
    (
        R,
        "31.6 mm",
        Measured(&["mass_ratios::alternating_light_and_heavy_tower_stands"]),
    ),
    (
        R,
        "4 cm",
        Measured(&["mass_ratios::thousandfold_mass_ratio_still_rests"]),
    ),
    (
        R,
        "0.2 mm",
        Setting("the default linear slop, the overlap a resting shape keeps"),
    ),
    (
        R,
        "1 cm",
        Input("mass_ratios::centimetre_and_millimetre_bodies_rest_on_a_plane_and_a_box"),
    ),
    (
        R,
        "2 mm",
        Input("mass_ratios::centimetre_and_millimetre_bodies_rest_on_a_plane_and_a_box"),
    ),
    (
        R,
        "0.11 mm",
        Measured(&["mass_ratios::centimetre_and_millimetre_bodies_rest_on_a_plane_and_a_box"]),
    ),
    (
        R,
        "1.1 %",
        Measured(&["mass_ratios::centimetre_and_millimetre_bodies_rest_on_a_plane_and_a_box"]),
    ),
    (
        R,
        "0.028 mm",
        Measured(&["mass_ratios::centimetre_and_millimetre_bodies_rest_on_a_plane_and_a_box"]),
    ),
    (
        R,
        "1.4 %",
        Measured(&["mass_ratios::centimetre_and_millimetre_bodies_rest_on_a_plane_and_a_box"]),
    ),
    // The header repeats the last two paragraphs in HearthShapeDef's and HearthWorldDef's docs.
    (
        H,
        "5.7 m",
        Measured(&["rolling::rolling_bodies_stop_after_the_analytic_distance"]),
    ),
    (
        H,
        "2 m/s",
        Input("rolling::rolling_bodies_stop_after_the_analytic_distance"),
    ),
    (
        H,
        "1.4 ×",
        Measured(&["rolling::rolling_bodies_stop_after_the_analytic_distance"]),
    ),
    (
        H,
        "0.031 mm",
        Measured(&["mass_ratios::heavy_box_on_a_light_box_rests_at_the_closed_form_height"]),
    ),
    (
        H,
        "4.3 mm",
        Measured(&["mass_ratios::hundred_kilograms_on_one_kilogram"]),
    ),
    (H, "100 kg", Input("mass_ratios::hundred_kilograms_on_one_kilogram")),
    (H, "5 s", Measured(&["mass_ratios::hundred_kilograms_on_one_kilogram"])),
    (
        H,
        "4 cm",
        Measured(&["mass_ratios::thousandfold_mass_ratio_still_rests"]),
    ),
    (
        H,
        "0.2 mm",
        Setting("the default linear slop, the overlap a resting shape keeps"),
    ),
    (
        H,
        "1 cm",
        Input("mass_ratios::centimetre_and_millimetre_bodies_rest_on_a_plane_and_a_box"),
    ),
    (H, "1 mm", Range),
    (
        H,
        "2 mm",
        Input("mass_ratios::centimetre_and_millimetre_bodies_rest_on_a_plane_and_a_box"),
    ),
    (
        H,
        "0.11 mm",
        Measured(&["mass_ratios::centimetre_and_millimetre_bodies_rest_on_a_plane_and_a_box"]),
    ),
    (
        H,
        "1.1 %",
        Measured(&["mass_ratios::centimetre_and_millimetre_bodies_rest_on_a_plane_and_a_box"]),
    ),
    (
        H,
        "0.028 mm",
        Measured(&["mass_ratios::centimetre_and_millimetre_bodies_rest_on_a_plane_and_a_box"]),
    ),
    (
        H,
        "1.4 %",
        Measured(&["mass_ratios::centimetre_and_millimetre_bodies_rest_on_a_plane_and_a_box"]),
    ),
    // ARCHITECTURE.
    (A, "6 Hz", History("the rigid Gauss-Seidel solver before the soft step")),
    (
        A,
        "0.4 mm",
        Measured(&["stacking::tower_of_30_boxes_stands_without_sleep"]),
    ),
    (
        A,
        "2.4 mm",
        Measured(&["stacking::tower_of_30_boxes_stands_without_sleep"]),
    ),
    (A, "162 °", Setting("where twist rows rest (joints/rows.rs)")),
    (
        A,
        "100 ×",
        Input("joints::heavy_chain_barely_stretches_and_does_not_jitter"),
    ),
    (A, "2.3 %", History("Gauss-Seidel alone, before the forest solve")),
    (A, "100 m", History("the f32 forest factorisation, before f64")),
    (
        A,
        "0.000 %",
        Measured(&["joints::heavy_chain_barely_stretches_and_does_not_jitter"]),
    ),
    (
        A,
        "0.03 rad",
        History("scalar rows solved alone, before the Schur coupling"),
    ),
    (A, "200 N·m", Input("joints::hinge_and_slider_limits_hold_under_load")),
    (A, "1 m", Input("joints::hinge_and_slider_limits_hold_under_load")),
    (
        A,
        "1.9 mm",
        Measured(&["joints::hinge_and_slider_limits_hold_under_load"]),
    ),
    // The header: its preamble repeats README's ranges; the rest are defaults and limits of
    // defs, each validated where the def is (src/capi, tests/c/test_*.c).
    (H, "0.1 s", Range),
    // The query functions (issue 14): the shape cast's tolerance and the longest translation.
    (
        H,
        "0.1 mm",
        Measured(&["queries::shape_casts_hit_at_the_analytic_time_of_impact"]),
    ),
    (H, "1e6 m", Measured(&["queries::bad_query_inputs_are_refused"])),
    (H, "10000 m", Range),
    (H, "100000 m", Range),
    (H, "10000 m/s", Range),
    (H, "10000 m/s²", Range),
    (H, "1e12 N", Range),
    (H, "1e10 N·s", Range),
    (H, "100000 kg/m³", Range),
    (H, "162 °", Setting("where twist rows rest")),
    // "0.1 m" in the header is also AABB_MARGIN (world.rs), a setting; the entry for the
    // debug draw's impulse scale above covers the figure.
    (
        H,
        "2 cm",
        Setting("SPECULATIVE_DISTANCE, the fixed part of the speculative distance (step.rs)"),
    ),
    (R, "1 m/s", Setting("the default hit_event_threshold (world.rs)")),
    (
        R,
        "3.35 m",
        Measured(&["events::a_one_way_platform_lets_a_box_up_through_and_holds_it_on_top"]),
    ),
    (
        R,
        "5 mm",
        Measured(&["events::a_one_way_platform_lets_a_box_up_through_and_holds_it_on_top"]),
    ),
    (H, "0 Hz", Setting("a joint spring's default: off")),
    (H, "1 kg", Setting("default masses of particles and soft bodies")),
    (H, "1e5 m", Range),
    (H, "1 m", Setting("defaults: spring rest length, explosion shock width")),
    (H, "1000 kg/m³", Setting("default shape density")),
    (
        H,
        "0.5 m",
        Setting("default half extent in the drag and buoyancy examples"),
    ),
    (H, "50 N·s", Setting("default explosion blast")),
    (H, "5 m", Setting("default explosion blast radius")),
    (H, "20 m/s", Setting("default shock speed")),
    (H, "100 N", Setting("default shock force and spring stiffness")),
    (H, "20 m", Setting("default shock range")),
    (H, "0.05 m", Setting("default particle radius")),
    (H, "0.5 rad", Setting("default burst cone")),
    (H, "1e4 m", Range),
    (H, "0.01 m", Setting("default soft-body vertex radius")),
    (
        H,
        "0.1 %",
        Setting("a convex hull's default weld tolerance, of its point cloud's size"),
    ),
    (H, "6 ×", Setting("the largest soft mesh index count, 6 × 1048576")),
    (H, "3 ×", Setting("a soft mesh's index count: 3 × triangles")),
    // Header: soft bodies (src/capi/soft.rs), the skin and a heavy body on the default ball.
    (
        H,
        "1 %",
        Measured(&["soft_robustness::the_default_skin_stays_within_one_percent_of_its_rest_lengths_up_to_nrt_1600"]),
    ),
    (
        H,
        "1600 J",
        Measured(&["soft_robustness::the_default_skin_stays_within_one_percent_of_its_rest_lengths_up_to_nrt_1600"]),
    ),
    (
        H,
        "40 kg",
        Input(
            "soft_robustness::a_box_twenty_times_the_ball_s_mass_does_not_get_in_or_push_the_skin_through_the_ground",
        ),
    ),
    (
        H,
        "0.3 m",
        Input(
            "soft_robustness::a_box_twenty_times_the_ball_s_mass_does_not_get_in_or_push_the_skin_through_the_ground",
        ),
    ),
    (
        H,
        "2 kg",
        Input(
            "soft_robustness::a_box_twenty_times_the_ball_s_mass_does_not_get_in_or_push_the_skin_through_the_ground",
        ),
    ),
    (
        H,
        "400 J",
        Input(
            "soft_robustness::a_box_twenty_times_the_ball_s_mass_does_not_get_in_or_push_the_skin_through_the_ground",
        ),
    ),
    (
        H,
        "1.5 cm",
        Measured(&[
            "soft_robustness::a_box_twenty_times_the_ball_s_mass_does_not_get_in_or_push_the_skin_through_the_ground",
        ]),
    ),
];

const UNITS: &[&str] = &[
    "m/s²", "m/s", "ms/step", "ms", "mm", "cm", "µs", "µg", "kg·m²", "kg/m³", "kg", "km", "N·m·s", "N·m", "N·s", "N",
    "rad/s", "rad", "Hz", "J", "%", "°", "×", "m", "s", "M", "B/body",
];

/// Every "number unit" in `text`: an ASCII number (digits, decimal point or thousands
/// comma, exponent) not glued to a word, then at most one space (or a line break), then a
/// unit that ends there.
fn scan(text: &str) -> Vec<String> {
    let b: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let starts = b[i].is_ascii_digit() && (i == 0 || !(b[i - 1].is_alphanumeric() || "._-/".contains(b[i - 1])));
        if !starts {
            i += 1;
            continue;
        }
        let mut j = i;
        while j < b.len()
            && (b[j].is_ascii_digit() || (",.".contains(b[j]) && j + 1 < b.len() && b[j + 1].is_ascii_digit()))
        {
            j += 1;
        }
        if j + 1 < b.len()
            && b[j] == 'e'
            && (b[j + 1].is_ascii_digit() || ("-+".contains(b[j + 1]) && j + 2 < b.len() && b[j + 2].is_ascii_digit()))
        {
            j += 2;
            while j < b.len() && b[j].is_ascii_digit() {
                j += 1;
            }
        }
        let number: String = b[i..j].iter().collect();
        let mut k = j;
        if k < b.len() && " \u{a0}\n".contains(b[k]) {
            k += 1;
        }
        let rest: String = b[k..b.len().min(k + 8)].iter().collect();
        for unit in UNITS {
            if let Some(after) = rest.strip_prefix(unit) {
                let next = after.chars().next();
                let last = unit.chars().last().unwrap();
                let glued = next.is_some_and(|c| c.is_alphanumeric() || (last.is_alphabetic() && "/·²³".contains(c)));
                if !glued {
                    out.push(format!("{number} {unit}"));
                    break;
                }
            }
        }
        i = j;
    }
    out
}

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// `fn name` in `tests/<file>.rs` with its doc comment and attributes (the lines right above
/// it), to the first line that is a lone `}`.
fn test_body(path: &str) -> String {
    let (file, name) = path.split_once("::").unwrap();
    let source = std::fs::read_to_string(root().join("tests").join(format!("{file}.rs")))
        .unwrap_or_else(|_| panic!("{path}: no tests/{file}.rs"));
    let fn_at = source
        .find(&format!("fn {name}("))
        .unwrap_or_else(|| panic!("{path}: no function {name} in tests/{file}.rs"));
    let mut start = source[..fn_at].rfind('\n').map_or(0, |i| i + 1);
    while start > 0 {
        let above = source[..start - 1].rfind('\n').map_or(0, |i| i + 1);
        let line = source[above..start - 1].trim_start();
        if !(line.starts_with("///") || line.starts_with("#[")) {
            break;
        }
        start = above;
    }
    let end = source[fn_at..].find("\n}\n").map_or(source.len(), |e| fn_at + e);
    source[start..end].to_string()
}

#[test]
fn every_documented_figure_is_listed() {
    let mut problems = Vec::new();
    let mut listed = BTreeSet::new();
    for &(doc, figure, _) in FIGURES {
        if !listed.insert((doc, figure)) {
            problems.push(format!("{doc}: {figure:?} listed twice"));
        }
    }
    for doc in [R, A, H, C] {
        let text = std::fs::read_to_string(root().join(doc)).unwrap();
        let found: BTreeSet<String> = scan(&text).into_iter().collect();
        for figure in &found {
            if !listed.contains(&(doc, figure.as_str())) {
                problems.push(format!(
                    "{doc} states {figure:?}: add it to FIGURES in tests/figures.rs with the test that asserts it"
                ));
            }
        }
        for &(d, figure, _) in FIGURES {
            if d == doc && !found.contains(figure) {
                problems.push(format!("{doc} no longer states {figure:?}: remove its FIGURES entry"));
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn every_figure_names_a_test_that_exists_and_quotes_it() {
    let mut problems = Vec::new();
    for &(doc, figure, backing) in FIGURES {
        let number = figure.split(' ').next().unwrap();
        match backing {
            Measured(tests) => {
                for t in tests {
                    let body = test_body(t);
                    if !body.contains(number) {
                        problems.push(format!("{doc} {figure:?}: {t} never mentions {number}"));
                    }
                }
            }
            Input(t) => {
                test_body(t);
            }
            Setting(why) | History(why) => assert!(!why.is_empty()),
            Range | Fact | Bench => {}
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// The f32 arithmetic the documents quote.
#[test]
fn f32_facts_the_documents_use() {
    let spacing = |x: f32| f32::from_bits(x.to_bits() + 1) - x;
    // README: "f32 resolves 8 mm at 100 km".
    assert!((spacing(100_000.0) - 0.0078125).abs() < 1e-9);
    // README: particle rods "within 2e-6 m, the f32 spacing of their coordinates" (8 to 10 m
    // from the origin: 9.5e-7 m).
    assert!(spacing(8.0) < 2e-6 && spacing(10.0) < 2e-6);
}

#[test]
fn the_scanner_finds_figures_and_nothing_else() {
    assert_eq!(
        scan("within 0.001 %, 1.9 mm, 1e-6 m, 2000 N·m, v2 m, x1.5 s, 3 ms/step, 4 metres, 10,000 kg"),
        ["0.001 %", "1.9 mm", "1e-6 m", "2000 N·m", "3 ms/step", "10,000 kg"]
    );
}
