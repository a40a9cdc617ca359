//! Dynamics: how bodies move.
//!
//! * `body` — rigid bodies: type, state, mass properties, per-body lists.
//! * `solver` — the sub-stepped solver: body arrays, integration, the sweeps.
//! * `integrate_wide` — plain bodies integrated four or eight at a time.
//! * `contact_solver`, `contact_wide` — contact constraints, coloured and solved in SIMD lanes.
//! * `joints` — ball, hinge, fixed, distance and slider joints; the exact forest solve.
//! * `island` — islands and sleep.

pub mod body;
pub mod contact_solver;
pub mod contact_wide;
pub mod integrate_wide;
pub mod island;
pub mod joints;
pub mod solver;
pub(crate) mod solver_stages;
