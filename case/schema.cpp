// The case-file schema (case/schema.hpp): one table of every key the reader accepts, and the
// reference generated from it (`swell help case`, docs/case_reference.md).
//
// Order matters: the reader lists allowed keys in table order in its messages, and the
// reference follows it. Keys shared by several forms of a section (a gauge's `at`) have one
// entry per meaning.
#include "case/schema.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace swell::case_schema {

namespace {

// The sections, in the reference's order. Function-local tables, so that readers in other
// translation units may use them during static initialisation.
const std::vector<Section>& section_table() {
  static const std::vector<Section> table = {
      {"", "", "", "", "The top level of a case file."},
      {"physics", "", "", "",
       "Fluid properties and the numerical models (defaults as DualSPHysics)."},
      {"physics.viscosity", "model", "artificial laminar", "",
       "The viscosity model and its coefficient."},
      {"physics.density_diffusion", "model", "fourtakas molteni none", "",
       "Density diffusion in the continuity equation: delta h c0 sum_b psi_ab . gradW_ab V_b."},
      {"physics.boundary", "model", "dbc mdbc", "",
       "The wall model of every boundary body: DBC, or mDBC (density from a ghost node mirrored "
       "across the wall)."},
      {"physics.shifting", "model", "none fickian", "",
       "Particle shifting after each step (Fickian, Lind et al. 2012 / Skillen et al. 2013)."},
      {"physics.corrections", "", "", "",
       "Kernel corrections of the SPH course, off by default: the corrected kernel gradient in "
       "the momentum equation (Bonet & Lok 1999) and a Shepard density re-initialisation."},
      {"time", "", "", "", "The run's end and the time integration."},
      {"time.settling", "", "", "",
       "A settling phase: every fluid velocity relaxed by exp(-sigma dt), sigma = rate (1 + cos(pi "
       "t / duration)) / 2, for t < duration."},
      {"domain", "", "", "",
       "The box that holds the run: particles that leave it are deleted (see Notes)."},
      {"output", "", "", "", "What is written to the output folder, and how often."},
      {"watchdog", "", "", "", "When a run counts as blown up (exit 3), checked every few steps."},
      {"limits", "", "", "", "What a case may ask of the machine before the fill starts."},
      {"bodies[]", "kind", "", "",
       "Each body: a fluid (a shape, or a fill of a tank) or a boundary (wall particles around or "
       "inside a shape, optionally moving). At least one fluid body."},
      {"bodies[].fill", "", "", "",
       "A fluid body given as every lattice point below a level inside a tank."},
      {"bodies[].shape", "", "", "",
       "A map with exactly one key naming the shape. Vectors take dim numbers."},
      {"bodies[].shape.box", "", "", "", "An axis-aligned box (a rectangle in 2D)."},
      {"bodies[].shape.cylinder", "dim", "2D 3D", "", "A disc (2D) or a cylinder (3D)."},
      {"bodies[].shape.sphere", "", "", "", "A sphere (a disc in 2D)."},
      {"bodies[].shape.polygon", "", "", "", "A simple polygon (2D cases only)."},
      {"bodies[].shape.mesh", "", "", "",
       "A triangle mesh (STL, OBJ, OFF, PLY) read with CGAL, placed by scale, then rotate, then "
       "translate; `stl:` is the same as `mesh:`."},
      {"bodies[].motion", "type", "linear sinusoidal rotation file wave", "wave",
       "`none` (the default), or a map whose keys depend on `type`; a wave paddle's also on "
       "`wave`. Angles, phases and rates in degrees."},
      {"bodies[].motion.absorption", "", "", "",
       "Active absorption at a piston (`true`, `false` or this map): U_c = G (eta_T - eta_M)."},
      {"gauges[]", "kind", "pressure height velocity force front runup", "",
       "Measurements written to gauges_<kind>.csv; the keys depend on `kind`."},
      {"damping[]", "zone shape", "plane box", "",
       "Damping zones (sponge layers): v *= exp(-sigma(s) dt) at depth s in [0, 1] into the zone; "
       "a zone is a `plane` or a `box`."},
      {"damping[].plane", "", "", "", "A plane zone's start plane and direction."},
      {"damping[].box", "", "", "", "A box zone's extent."},
  };
  return table;
}

// clang-format off
const std::vector<Key>& key_table() {
  static const std::vector<Key> table = {
    // --- top level ---
    {"", "name", "", "name", "the case file's stem (other characters become _)", "",
     "1 to 100 characters from A-Z a-z 0-9 . _ -, not starting with '.'",
     "case name: names the output folder out/<name> and the files in it"},
    {"", "dim", "", "integer", "required", "", "2 | 3", "dimension of the case"},
    {"", "dp", "", "number", "required", "m", "> 0",
     "particle spacing: every body is filled on the lattice (i + 1/2) dp"},
    {"", "physics", "", "map", "all defaults", "", "", "fluid properties and models (physics.*)"},
    {"", "time", "", "map", "required", "", "", "end time and integrator (time.*)"},
    {"", "domain", "", "map", "the particles' box + 10 % + 2h per side, + 50 % of its height above", "", "",
     "the box outside which particles are deleted (domain.*, Notes)"},
    {"", "bodies", "", "list of maps", "required", "", "at least one fluid body",
     "fluid and boundary bodies (bodies[].*)"},
    {"", "gauges", "", "list of maps", "none", "", "", "measurements (gauges[].*)"},
    {"", "output", "", "map", "all defaults", "", "", "output schedule and formats (output.*)"},
    {"", "watchdog", "", "map", "all defaults", "", "", "blow-up thresholds (watchdog.*)"},
    {"", "limits", "", "map", "all defaults", "", "", "size limits (limits.*)"},
    {"", "damping", "", "list of maps", "none", "", "", "damping zones (damping[].*)"},

    // --- physics ---
    {"physics", "rho0", "", "number", "1000", "kg/m^3", "> 0", "reference density of the fluid"},
    {"physics", "gravity", "", "vector", "[0, -9.81] (2D), [0, 0, -9.81] (3D)", "m/s^2", "non-zero",
     "gravity; the vertical is the last axis"},
    {"physics", "coefsound", "", "number", "20", "", "> 0",
     "c0 = coefsound sqrt(|g| hswl): the speed of sound as a multiple of the shallow-water speed"},
    {"physics", "coefh", "", "number", "1.0", "", "[0.5, 4]", "h = coefh sqrt(dim) dp"},
    {"physics", "hswl", "", "number", "the fluid's height: top - bottom fluid particle + dp", "m", "> 0",
     "still-water height used for c0"},
    {"physics", "kernel", "", "choice", "wendland", "", "wendland | cubic | quintic | gaussian",
     "smoothing kernel; support 2h (wendland, cubic) or 3h (quintic, gaussian)"},
    {"physics", "viscosity", "", "map", "{model: artificial, alpha: 0.01}", "", "", "physics.viscosity.*"},
    {"physics", "density_diffusion", "", "map", "{model: fourtakas, delta: 0.1}", "", "",
     "physics.density_diffusion.*"},
    {"physics", "density_bounds", "", "[min, max]", "[0.7, 1.3]", "rho0", "0 < min <= 1 <= max, min < max",
     "fluid particles whose density leaves [min, max] rho0 are deleted (counted)"},
    {"physics", "boundary", "", "map", "{model: dbc}", "", "", "physics.boundary.*"},
    {"physics", "shifting", "", "map", "{model: none}", "", "", "physics.shifting.*"},
    {"physics", "corrections", "", "map", "all off", "", "", "physics.corrections.*"},

    {"physics.viscosity", "model", "", "choice", "artificial", "", "artificial | laminar",
     "artificial: Monaghan (1992); laminar: Lo & Shao"},
    {"physics.viscosity", "alpha", "artificial", "number", "0.01", "", ">= 0",
     "artificial viscosity coefficient: Pi_ab = -alpha cbar mu_ab / rhobar_ab"},
    {"physics.viscosity", "nu", "laminar", "number", "1e-6", "m^2/s", ">= 0", "kinematic viscosity"},

    {"physics.density_diffusion", "model", "", "choice", "fourtakas", "", "fourtakas | molteni | none",
     "fourtakas: Fourtakas et al. (2019), on the dynamic density; molteni: Molteni & Colagrossi"},
    {"physics.density_diffusion", "delta", "fourtakas molteni", "number", "0.1", "", ">= 0",
     "diffusion coefficient delta"},

    {"physics.boundary", "model", "", "choice", "dbc", "", "dbc | mdbc",
     "dbc: dynamic boundary conditions; mdbc: modified DBC (English et al. 2022)"},
    {"physics.boundary", "slip", "mdbc", "choice", "wall", "", "wall | noslip | freeslip",
     "velocity the walls show the fluid: the body's, 2 v_body - v_ghost, or the ghost's mirrored"},
    {"physics.boundary", "pressure", "mdbc", "choice", "linear", "", "linear | hydrostatic",
     "wall density from the ghost's: linear, rho_g + (x_w - x_g).grad rho_g (English et al. "
     "2022); hydrostatic, p_w = p_g + rho0 (g - a_w).(x_w - x_g) (English et al. 2025)"},
    {"physics.boundary", "det_min", "mdbc", "number", "1e-3", "", "(0, 1)",
     "below this determinant of the ghost's correction matrix: Shepard average instead"},

    {"physics.corrections", "kernel_gradient", "", "choice", "none", "", "none | kgc",
     "kgc: dv/dt = L_a (pressure + artificial-viscosity sum) + g, L_a the kernel-gradient "
     "correction matrix; artificial viscosity only"},
    {"physics.corrections", "det_min", "", "number", "0.1", "", "(0, 1)",
     "kgc: below this determinant of the moment matrix, no correction (isolated particles)"},
    {"physics.corrections", "shepard_reinit", "", "integer", "0", "steps", ">= 0",
     "every this many steps the fluid density is re-initialised by Shepard interpolation "
     "(0: never)"},
    {"physics.shifting", "model", "", "choice", "none", "", "none | fickian", "shifting model"},
    {"physics.shifting", "coefficient", "fickian", "number", "2", "", "(0, 10]",
     "A in dr = -A h |v| dt grad C"},
    {"physics.shifting", "surface_threshold", "fickian", "number", "1.5 (2D), 2.75 (3D)", "", "(0, dim)",
     "free surface where div r is below it: tangential shift only"},
    {"physics.shifting", "correct_density", "fickian", "bool", "false", "", "true | false",
     "move each shifted particle's density with it: rho += dr . grad rho (Lind et al. 2012)"},
    {"physics.shifting", "mode", "fickian", "choice", "full", "", "full | nobound | nofixed",
     "fluid particles near walls: shifted (full), not shifted with a wall particle within the "
     "kernel support (nobound) or a fixed-wall particle (nofixed); DualSPHysics' ShiftMode"},

    // --- time ---
    {"time", "end", "", "number", "required", "s", "> 0", "end time of the run"},
    {"time", "cfl", "", "number", "0.2", "", "(0, 1]",
     "dt = cfl min(dt_f, dt_cv[, dt_nu]) (run header prints the terms)"},
    {"time", "dt_fixed", "", "number", "none: the CFL step", "s", "> 0",
     "a fixed time step instead of the CFL choice (DualSPHysics' DtFixed); above the CFL step "
     "a run may go unstable (watchdog, exit 3)"},
    {"time", "integrator", "", "choice", "symplectic", "", "symplectic | verlet",
     "time integration (symplectic: two force evaluations per step)"},
    {"time", "verlet_steps", "", "integer", "40", "steps", ">= 1",
     "verlet: one Euler step every verlet_steps steps"},
    {"time", "settling", "", "map", "none", "", "", "settling phase (time.settling.*)"},
    {"time.settling", "duration", "", "number", "required", "s", "> 0", "length T of the phase"},
    {"time.settling", "rate", "", "number", "10", "1/s", "> 0", "sigma_0"},

    // --- domain ---
    {"domain", "min", "", "vector", "required", "m", "", "lower corner"},
    {"domain", "max", "", "vector", "required", "m", "> min on every axis", "upper corner"},
    {"domain", "periodic", "", "list of axes", "none", "", "x y (z in 3D)",
     "periodic axes: the domain's extent on each is the period (at least two kernel supports); "
     "particles leaving through one face enter through the other and interact across it"},

    // --- output ---
    {"output", "every", "", "number", "0: only the initial and final states", "s", ">= 0",
     "snapshot interval (VTK, HDF5)"},
    {"output", "vtk", "", "bool", "true", "", "true | false", "write <name>.pvd and vtk/*.vtp"},
    {"output", "vtk_split", "", "bool", "false", "", "true | false",
     "also write fluid-only and boundary-only .vtp series"},
    {"output", "hdf5", "", "bool", "true", "", "true | false", "write snapshots and metadata to <name>.h5"},
    {"output", "checkpoint_every", "", "number", "0: at every output time", "s", ">= 0",
     "checkpoint interval (restart)"},
    {"output", "gauge_every", "", "number", "output.every / 10 (time.end / 10 without output.every)", "s",
     "> 0", "default gauge interval"},

    // --- watchdog ---
    {"watchdog", "every", "", "integer", "10", "steps", "[1, 1000]", "steps between checks"},
    {"watchdog", "warn_excluded", "", "number", "0.001", "of the fluid mass", "(0, 1]",
     "warn once when this fraction of the fluid has been deleted"},
    {"watchdog", "max_excluded", "", "number", "0.05", "of the fluid mass", "(0, 1]",
     "stop when this fraction of the fluid has been deleted"},
    {"watchdog", "max_density", "", "number", "2", "rho0", "> 1",
     "stop on a density above f rho0 or below rho0 / f"},
    {"watchdog", "penetration_depth", "", "number", "2", "dp", "> 0",
     "fluid this deep below the lowest wall particle has leaked through the floor"},
    {"watchdog", "max_penetrated", "", "number", "0.001", "of the fluid", "[0, 1]",
     "stop when more than this fraction has leaked through the floor"},
    {"watchdog", "dt_collapse", "", "number", "1e-3", "of the first dt", "(0, 1)",
     "stop when dt falls below this fraction of the first dt"},

    // --- limits ---
    {"limits", "max_particles", "", "number", "5e7", "particles", ">= 1",
     "refuse a case whose estimated particle count exceeds it"},

    // --- bodies ---
    {"bodies[]", "name", "", "name", "required", "", "non-empty, unique", "body name"},
    {"bodies[]", "kind", "", "choice", "required", "", "fluid | boundary", "what the body is"},
    {"bodies[]", "shape", "", "map", "required (fluid: shape or fill)", "", "", "the body's shape (bodies[].shape.*)"},
    {"bodies[]", "fill", "fluid", "map", "none", "", "", "instead of a shape: a fill of a tank (bodies[].fill.*)"},
    {"bodies[]", "walls", "boundary", "choice", "inside", "", "inside | outside",
     "inside: the fluid is inside the shape (a tank); outside: a solid structure (see Notes)"},
    {"bodies[]", "layers", "boundary", "integer", "3", "particles", ">= 1",
     "wall thickness in particles (see Notes for how many the kernel needs)"},
    {"bodies[]", "open", "boundary", "list of faces", "none", "", "xmin xmax ymin ymax (zmin zmax in 3D)",
     "faces of the shape's box left without walls (an open tank top)"},
    {"bodies[]", "motion", "boundary", "none | map", "none", "", "", "prescribed motion (bodies[].motion.*)"},
    {"bodies[]", "boundary", "boundary", "choice", "physics.boundary.model", "", "dbc | mdbc",
     "this body's wall model (e.g. mDBC on the structure whose loads matter, DBC elsewhere)"},

    {"bodies[].fill", "below", "", "number", "required", "m", "", "level (vertical coordinate) the fill reaches"},
    {"bodies[].fill", "inside", "", "name", "required", "", "a boundary body with walls: inside",
     "the tank to fill"},

    {"bodies[].shape", "box", "", "map", "", "", "", "bodies[].shape.box.*"},
    {"bodies[].shape", "cylinder", "", "map", "", "", "", "bodies[].shape.cylinder.*"},
    {"bodies[].shape", "sphere", "", "map", "", "", "", "bodies[].shape.sphere.*"},
    {"bodies[].shape", "polygon", "", "map", "", "", "2D only", "bodies[].shape.polygon.*"},
    {"bodies[].shape", "mesh", "", "map", "", "", "", "bodies[].shape.mesh.*"},
    {"bodies[].shape", "stl", "", "map", "", "", "", "the same as mesh"},
    {"bodies[].shape", "union", "", "list of shapes", "", "", ">= 2 shapes", "the union of the shapes"},
    {"bodies[].shape", "difference", "", "list of shapes", "", "", ">= 2 shapes",
     "the first shape minus all the others"},

    {"bodies[].shape.box", "min", "", "vector", "required", "m", "", "lower corner"},
    {"bodies[].shape.box", "max", "", "vector", "required", "m", "> min on every axis", "upper corner"},
    {"bodies[].shape.cylinder", "center", "2D", "vector", "required", "m", "", "centre of the disc"},
    {"bodies[].shape.cylinder", "p1", "3D", "vector", "required", "m", "", "one end of the axis"},
    {"bodies[].shape.cylinder", "p2", "3D", "vector", "required", "m", "!= p1", "the other end of the axis"},
    {"bodies[].shape.cylinder", "radius", "2D 3D", "number", "required", "m", "> 0", "radius"},
    {"bodies[].shape.sphere", "center", "", "vector", "required", "m", "", "centre"},
    {"bodies[].shape.sphere", "radius", "", "number", "required", "m", "> 0", "radius"},
    {"bodies[].shape.polygon", "points", "", "list of [x, y]", "required", "m",
     ">= 3 points, simple, non-zero area, not closed by repeating the first", "corners in order"},
    {"bodies[].shape.mesh", "file", "", "string", "required", "", ".stl .obj .off .ply (any case)",
     "mesh file, relative to the case file's folder"},
    {"bodies[].shape.mesh", "scale", "", "number | [sx, sy, sz]", "1", "", "> 0", "scale factor(s), first"},
    {"bodies[].shape.mesh", "rotate", "", "[rx, ry, rz]", "[0, 0, 0]", "deg", "",
     "rotation about x, then y, then z, after the scale"},
    {"bodies[].shape.mesh", "translate", "", "[x, y, z]", "[0, 0, 0]", "m", "", "translation, last"},
    {"bodies[].shape.mesh", "repair", "", "bool", "false", "", "true | false",
     "fill holes and remove self-intersections instead of refusing the mesh"},
    {"bodies[].shape.mesh", "slice_y", "", "number", "required in 2D", "m", "2D only",
     "a 2D case uses the section y = slice_y of the placed mesh, its (x, z) as (x, y)"},

    // --- motion: every type ---
    {"bodies[].motion", "type", "", "choice", "required", "", "linear | sinusoidal | rotation | file | wave",
     "the motion law"},
    {"bodies[].motion", "start", "", "number", "0", "s", ">= 0", "the motion starts (local time tau = t - start)"},
    {"bodies[].motion", "stop", "", "number", ".inf", "s", "> start", "the body stops (held at its pose)"},
    {"bodies[].motion", "ramp", "", "number", "0 (wave: 2 T or 2 Tp; solitary: none)", "s", ">= 0",
     "smoothstep ramp of the velocity (constant laws) or displacement (the others)"},
    // linear
    {"bodies[].motion", "velocity", "linear", "vector", "zero (velocity and/or acceleration required)", "m/s", "",
     "velocity"},
    {"bodies[].motion", "acceleration", "linear", "vector", "zero", "m/s^2", "", "acceleration"},
    // sinusoidal
    {"bodies[].motion", "amplitude", "sinusoidal", "number", "required", "m", "", "displacement amplitude"},
    {"bodies[].motion", "period", "sinusoidal", "number", "required", "s", "> 0", "period"},
    {"bodies[].motion", "phase", "sinusoidal", "number", "0", "deg", "", "phase"},
    {"bodies[].motion", "direction", "sinusoidal", "vector", "+x", "", "non-zero", "direction of the displacement"},
    // rotation
    {"bodies[].motion", "centre", "rotation", "vector", "required", "m", "", "centre of rotation"},
    {"bodies[].motion", "axis", "rotation", "[x, y, z]", "[0, 0, 1]", "", "non-zero; 2D: [0, 0, +-1]",
     "rotation axis"},
    {"bodies[].motion", "rate", "rotation", "number", "rate, or amplitude and period, required", "deg/s", "",
     "constant angular rate"},
    {"bodies[].motion", "amplitude", "rotation", "number", "", "deg", "", "angle amplitude (with period)"},
    {"bodies[].motion", "period", "rotation", "number", "", "s", "> 0", "period of the oscillation"},
    {"bodies[].motion", "phase", "rotation", "number", "0", "deg", "", "phase of the oscillation"},
    // file
    {"bodies[].motion", "file", "file", "string", "required", "", "CSV: header, time and value columns",
     "motion record, relative to the case file's folder; C1 cubic Hermite interpolation"},
    {"bodies[].motion", "column", "file", "name", "the second column", "", "a column of the header",
     "value column by header name"},
    {"bodies[].motion", "quantity", "file", "choice", "required", "", "displacement | angle",
     "displacement [m] along direction, or angle [deg] about centre and axis"},
    {"bodies[].motion", "direction", "file", "vector", "+x", "", "non-zero; displacement only",
     "direction of the displacement"},
    {"bodies[].motion", "centre", "file", "vector", "required for angle", "m", "angle only", "centre of rotation"},
    {"bodies[].motion", "axis", "file", "[x, y, z]", "[0, 0, 1]", "", "angle only; 2D: [0, 0, +-1]", "rotation axis"},
    // wave paddle
    {"bodies[].motion", "paddle", "wave", "choice", "piston", "", "piston | flap", "paddle type"},
    {"bodies[].motion", "wave", "wave", "choice", "required", "", "regular | solitary | focused | irregular",
     "the wave to make"},
    {"bodies[].motion", "depth", "wave", "number", "required", "m", "> 0", "still-water depth at the paddle"},
    {"bodies[].motion", "direction", "wave", "vector", "+x", "", "horizontal, non-zero", "direction of the waves"},
    {"bodies[].motion", "hinge", "wave", "vector", "required for a flap", "m", "flap only; below the still-water level",
     "the flap's hinge point"},
    {"bodies[].motion", "bed", "wave", "number", "0", "m", "", "vertical coordinate of the bed at the paddle"},
    {"bodies[].motion", "height", "wave:regular wave:solitary", "number", "required", "m", "> 0",
     "wave height H (solitary: crest above the still water)"},
    {"bodies[].motion", "period", "wave:regular", "number", "required", "s", "> 0", "wave period T"},
    {"bodies[].motion", "order", "wave:regular wave:irregular wave:focused", "integer", "1", "",
     "1 | 2 (2: pistons only)",
     "generation order (2: Madsen 1971; irregular, focused: with the bound long wave)"},
    {"bodies[].motion", "phase", "wave:regular", "number", "0", "deg", "", "phase of the paddle signal"},
    {"bodies[].motion", "hs", "wave:irregular", "number", "required", "m", "> 0", "significant wave height Hm0"},
    {"bodies[].motion", "tp", "wave:irregular wave:focused", "number", "required", "s", "> 0", "peak period"},
    {"bodies[].motion", "gamma", "wave:irregular wave:focused", "number", "3.3", "", "[1, 20]",
     "JONSWAP peak enhancement"},
    {"bodies[].motion", "spectrum", "wave:irregular wave:focused", "choice", "jonswap", "", "jonswap | pm",
     "spectral shape (pm: Pierson-Moskowitz)"},
    {"bodies[].motion", "components", "wave:irregular wave:focused", "integer", "200 (focused: 60)", "",
     "[1, 5000]", "number of frequency components"},
    {"bodies[].motion", "seed", "wave:irregular", "integer", "1", "", ">= 0", "seed of the random phases"},
    {"bodies[].motion", "f_min", "wave:irregular wave:focused", "number", "0.5 / tp", "Hz", "> 0, < f_max",
     "lowest frequency"},
    {"bodies[].motion", "f_max", "wave:irregular wave:focused", "number", "3 / tp", "Hz", "> 0, > f_min",
     "highest frequency"},
    {"bodies[].motion", "amplitude", "wave:focused", "number", "required", "m", "> 0",
     "linear crest amplitude at the focus"},
    {"bodies[].motion", "focus_distance", "wave:focused", "number", "required", "m", "> 0",
     "distance of the focus from the paddle"},
    {"bodies[].motion", "focus_time", "wave:focused", "number", "required", "s", "> 0",
     "time of focus after the motion's start"},
    {"bodies[].motion", "absorption", "wave", "bool | map", "false", "", "pistons only",
     "active absorption (bodies[].motion.absorption.*)"},

    {"bodies[].motion.absorption", "gain", "", "choice", "tuned (solitary: shallow)", "", "tuned | shallow",
     "G = w_p / F(k_p d) (tuned) or sqrt(g / d) (shallow)"},
    {"bodies[].motion.absorption", "distance", "", "number", "one kernel support (2h or 3h)", "m", "> 0",
     "paddle face to the measuring line"},
    {"bodies[].motion.absorption", "filter", "", "number", "0.02 T_p", "s", ">= 0 (0: off)",
     "low-pass time constant of the error eta_M - eta_T"},
    {"bodies[].motion.absorption", "drift", "", "number", "10 T_p", "s", "> 0",
     "time constant pulling the correction back to zero"},

    // --- gauges ---
    {"gauges[]", "name", "", "name", "required", "", "letters, digits, _ and -; unique", "CSV column name"},
    {"gauges[]", "kind", "", "choice", "required", "", "pressure | height | velocity | force | front | runup",
     "what is measured"},
    {"gauges[]", "every", "", "number", "output.gauge_every", "s", "> 0; or step",
     "sampling interval; step: a row after every step (the raw series)"},
    {"gauges[]", "at", "pressure", "vector", "required", "m", "inside the domain", "probe point"},
    {"gauges[]", "normal", "pressure", "vector", "none", "", "non-zero",
     "wall normal into the fluid: the probe samples at at + offset normal"},
    {"gauges[]", "offset", "pressure", "number", "h", "m", ">= 0; needs normal", "distance along the normal"},
    {"gauges[]", "size", "pressure", "number", "none (a point probe)", "m", "> 0; needs normal",
     "sensor face: disc diameter (3D) or segment length (2D); interval means"},
    {"gauges[]", "at", "height", "vector", "required", "m", "inside the domain",
     "start of the vertical measuring line (its position, and the floor)"},
    {"gauges[]", "level", "height", "choice", "surface", "", "surface | integral",
     "first free surface above the start, or start + integral of the water fraction"},
    {"gauges[]", "sampling", "height", "choice", "instant", "", "instant | mean",
     "level at each row's time, or the mean over each interval (evaluated every step)"},
    {"gauges[]", "at", "velocity", "vector", "required", "m", "inside the domain", "probe point"},
    {"gauges[]", "body", "force", "name", "required", "", "a boundary body", "body whose fluid load is measured"},
    {"gauges[]", "moment_about", "force", "vector", "the origin", "m", "", "moment reference point"},
    {"gauges[]", "band", "front", "number", "2h", "m", "> 0",
     "height above the initial fluid bottom within which fluid counts (see Notes)"},
    {"gauges[]", "from", "runup", "vector", "required", "m", "below the lowest shoreline",
     "lower end of the line along the slope"},
    {"gauges[]", "to", "runup", "vector", "required", "m", "higher than from, not straight above it",
     "upper end of the line along the slope"},
    {"gauges[]", "swl", "runup", "number", "none: absolute elevation", "m", "",
     "still-water level the runup is given above"},
    {"gauges[]", "sampling", "runup", "choice", "instant", "", "instant | max",
     "runup at each row's time, or the largest within each interval"},
    {"gauges[]", "edge", "runup", "choice", "highest", "", "highest | connected",
     "the highest wet point of the line, or the edge of the tongue attached to the sea (a wet "
     "stretch cut off by a dry one longer than the kernel support, a splash, does not count)"},

    // --- damping ---
    {"damping[]", "name", "", "name", "required", "", "non-empty, unique", "zone name"},
    {"damping[]", "ramp", "", "choice", "quadratic", "", "quadratic | cosine",
     "sigma(s) = rate s^2, or rate (1 - cos(pi s)) / 2"},
    {"damping[]", "rate", "", "number", "10", "1/s", "> 0", "sigma_max"},
    {"damping[]", "components", "", "list of axes", "all", "", "x y (z in 3D), each once",
     "damped velocity components"},
    {"damping[]", "start", "", "number", "0", "s", ">= 0", "active from"},
    {"damping[]", "stop", "", "number", ".inf", "s", "> start", "active until"},
    {"damping[]", "plane", "plane", "map", "", "", "", "damping[].plane.*"},
    {"damping[]", "length", "plane", "number", "required", "m", "> 0", "zone length L along the direction"},
    {"damping[]", "box", "box", "map", "", "", "", "damping[].box.*"},
    {"damping[]", "direction", "box", "vector", "required", "", "non-zero",
     "direction of growing s across the box"},
    {"damping[].plane", "at", "", "vector", "required", "m", "", "a point of the plane where the zone starts"},
    {"damping[].plane", "direction", "", "vector", "required", "", "non-zero", "normal pointing into the zone"},
    {"damping[].box", "min", "", "vector", "required", "m", "", "lower corner"},
    {"damping[].box", "max", "", "vector", "required", "m", "> min on every axis", "upper corner"},
  };
  return table;
}
// clang-format on

Names split(std::string_view s, std::string_view sep) {
  Names out;
  std::size_t pos = 0;
  while (pos <= s.size()) {
    const std::size_t next = s.find(sep, pos);
    const std::string_view part =
        s.substr(pos, next == std::string_view::npos ? s.npos : next - pos);
    if (!part.empty()) out.push_back(part);
    if (next == std::string_view::npos) break;
    pos = next + sep.size();
  }
  return out;
}

bool has(const Names& names, std::string_view name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

void add_once(Names& names, std::string_view name) {
  if (!has(names, name)) names.push_back(name);
}

// Whether a key's forms include `form` (a form also owns its sub-forms: "wave" owns
// "wave:regular").
bool in_form(const Key& k, std::string_view form) {
  for (const std::string_view f : split(k.forms, " ")) {
    if (f == form) return true;
    if (f.size() > form.size() && f.substr(0, form.size()) == form && f[form.size()] == ':')
      return true;
  }
  return false;
}

}  // namespace

const std::vector<Section>& sections() {
  return section_table();
}
const std::vector<Key>& keys() {
  return key_table();
}

const Section& section(std::string_view path) {
  for (const Section& s : sections())
    if (s.path == path) return s;
  throw std::logic_error("case schema: no section '" + std::string(path) + "'");
}

Names all_keys(std::string_view sec) {
  section(sec);
  Names out;
  for (const Key& k : keys())
    if (k.section == sec) add_once(out, k.name);
  return out;
}

Names common_keys(std::string_view sec) {
  section(sec);
  Names out;
  for (const Key& k : keys())
    if (k.section == sec && k.forms.empty()) add_once(out, k.name);
  return out;
}

Names form_keys(std::string_view sec, std::string_view form) {
  section(sec);
  Names out;
  for (const Key& k : keys())
    if (k.section == sec && in_form(k, form)) add_once(out, k.name);
  return out;
}

Names keys_for(std::string_view sec, std::string_view form) {
  Names out = common_keys(sec);
  for (const std::string_view k : form_keys(sec, form)) add_once(out, k);
  return out;
}

Names forms(std::string_view sec, std::string_view parent) {
  const Section& s = section(sec);
  if (parent.empty()) return split(s.forms, " ");
  // Sub-forms are the choices of the sub-selector key (a wave motion's `wave`).
  if (s.subselector.empty() || !has(split(s.forms, " "), parent))
    throw std::logic_error("case schema: '" + std::string(sec) + "' has no sub-forms of '" +
                           std::string(parent) + "'");
  return choices(sec, s.subselector);
}

Names choices(std::string_view sec, std::string_view key) {
  for (const Key& k : keys())
    if (k.section == sec && k.name == key && k.type == "choice") return split(k.allowed, " | ");
  throw std::logic_error("case schema: no choice key '" + std::string(key) + "' in '" +
                         std::string(sec) + "'");
}

// ---------------------------------------------------------------------------------------------
// The reference

namespace {

std::string key_path(const Key& k) {
  return k.section.empty() ? std::string(k.name)
                           : std::string(k.section) + "." + std::string(k.name);
}

// "model: laminar", "type: wave, wave: regular", "2D", "kind: boundary".
std::string form_text(const Section& s, const Key& k) {
  if (k.forms.empty()) return "";
  std::string out;
  for (const std::string_view f : split(k.forms, " ")) {
    if (!out.empty()) out += "; ";
    const std::size_t colon = f.find(':');
    if (s.selector == "dim") {
      out += f;
    } else if (colon == std::string_view::npos) {
      out += std::string(s.selector) + ": " + std::string(f);
    } else {
      out += std::string(s.selector) + ": " + std::string(f.substr(0, colon)) + ", " +
             std::string(s.subselector) + ": " + std::string(f.substr(colon + 1));
    }
  }
  return out;
}

// A table cell: | would end the cell.
std::string cell(std::string_view s) {
  std::string out;
  for (const char c : s) {
    if (c == '|')
      out += "\\|";
    else
      out += c;
  }
  return out.empty() ? "" : out;
}

std::string joined(const Names& names) {
  std::string out;
  for (const std::string_view n : names) out += (out.empty() ? "" : ", ") + std::string(n);
  return out;
}

std::string section_title(const Section& s) {
  return s.path.empty() ? std::string("Top level") : "`" + std::string(s.path) + "`";
}

void write_row(std::ostringstream& o, const Section& s, const Key& k) {
  o << "| `" << key_path(k) << "` | " << cell(form_text(s, k)) << " | " << cell(k.type) << " | "
    << cell(k.default_value) << " | " << cell(k.unit) << " | " << cell(k.allowed) << " | "
    << cell(k.description) << " |\n";
}

void write_section(std::ostringstream& o, const Section& s) {
  o << "## " << section_title(s) << "\n\n" << s.description << "\n";
  if (!s.selector.empty() && s.selector != "kind" && !s.forms.empty()) {
    // A selector that is a key of the section is written as code; "dim", "zone shape" are not.
    const bool is_key = has(all_keys(s.path), s.selector);
    o << "\nForms (by "
      << (s.selector == "dim" ? "the case's dim"
          : is_key            ? "`" + std::string(s.selector) + "`"
                              : std::string(s.selector) + ": the key given")
      << "): " << std::string(s.forms) << ". A key of another form is an error.";
    if (!s.subselector.empty()) {
      // The form with sub-forms: the prefix of the first "form:sub" in the section's keys.
      std::string parent;
      for (const Key& k : keys())
        for (const std::string_view f : split(k.forms, " "))
          if (parent.empty() && k.section == s.path && f.find(':') != std::string_view::npos)
            parent = std::string(f.substr(0, f.find(':')));
      o << " With `" << s.selector << ": " << parent << "` the keys also depend on `"
        << s.subselector << "`: " << joined(choices(s.path, s.subselector)) << ".";
    }
    o << "\n";
  } else if (!s.selector.empty() && !s.forms.empty()) {
    o << "\nKinds (by `" << s.selector << "`): " << std::string(s.forms)
      << ". A key of another kind is an error.\n";
  }
  o << "\n| key | for | type | default | unit | allowed | description |\n"
    << "|---|---|---|---|---|---|---|\n";
  for (const Key& k : keys())
    if (k.section == s.path) write_row(o, s, k);
  o << "\n";
}

const char* const kIntro =
    "# Case-file reference\n"
    "\n"
    "Generated by `swell help case` from the case-file reader's schema (case/schema.cpp), the "
    "table the reader takes its allowed keys from; do not edit by hand: run `swell help case > "
    "docs/case_reference.md` (tests/test_case_reference.cpp fails when this file is stale). "
    "`swell help case KEY.PATH` prints one entry (`swell help case physics.coefh`, `swell help "
    "case "
    "gauges.band`).\n"
    "\n"
    "Conventions: key paths are written as in error messages, with list items as `[]` "
    "(`bodies[].motion.period`). A vector takes `dim` numbers (z stays 0 in 2D); quantities are SI "
    "unless the unit says otherwise; angles, phases and rates of motions are in degrees. \"for\" "
    "names the form of the section that takes the key (the model, kind or type it belongs to); "
    "empty: every form. A misspelt or misplaced key, a wrong type or a value out of range is an "
    "error `case.yaml:LINE: key.path: what was expected` (exit 2).\n"
    "\n"
    "## Derived quantities\n"
    "\n"
    "Computed by the set-up (case/setup.cpp) and the solver, and printed with their values in "
    "the header of `swell run`:\n"
    "\n"
    "| quantity | formula | notes |\n"
    "|---|---|---|\n"
    "| smoothing length | `h = coefh sqrt(dim) dp` | DualSPHysics' convention; kernel support 2h "
    "(wendland, cubic) or 3h (quintic, gaussian) |\n"
    "| still-water height | `hswl` as given, else `z_top - z_bottom + dp` of the fluid particles "
    "(along gravity) | from the fluid particles at t = 0 |\n"
    "| speed of sound | `c0 = coefsound sqrt(\\|g\\| hswl)` | |\n"
    "| Tait's B | `B = c0^2 rho0 / gamma`, `gamma = 7` | `P = B ((rho / rho0)^gamma - 1)` |\n"
    "| particle mass | `m = rho0 dp^dim` | every particle, fluid and wall |\n"
    "| time step | `dt = cfl min(dt_f, dt_cv[, dt_nu])` | `dt_f = sqrt(h / max\\|a\\|)` over the "
    "fluid; `dt_cv = h / (max c + max_ab h \\|v_ab . r_ab\\| / (r_ab^2 + eta^2))`, `eta^2 = 0.01 "
    "h^2` (Monaghan & Kos 1999); `dt_nu = 0.125 h^2 / nu` with laminar viscosity only. At rest "
    "`dt_cv = h / c0` |\n"
    "\n";

const char* const kNotes =
    "## Notes\n"
    "\n"
    "### `domain`: particles that leave it are deleted\n"
    "\n"
    "The domain is the box of the run's neighbour grid. A particle whose position leaves it (any "
    "face) is excluded at the next sort: moved out of the active particles, never computed again, "
    "and counted by face and time in the summary (`excluded.<face>` in the checkpoint). Fluid "
    "particles with a non-finite state or a density outside `physics.density_bounds` are deleted "
    "the same way. The watchdog warns at `watchdog.warn_excluded` and stops the run (exit 3) at "
    "`watchdog.max_excluded` of the fluid mass. Without `domain:` the box is the bounding box of "
    "every particle and of every moving body's path up to `time.end`, plus 10 % of its size and "
    "2h on each side, plus a further 50 % of its height above (against gravity), so a splash "
    "thrown out of an open tank falls back in. An explicit domain must hold every particle at "
    "t = 0 and every moving body's path (else a case error), and every gauge point.\n"
    "\n"
    "### `layers`: how many wall layers the kernel needs\n"
    "\n"
    "Wall particles sit on the lattice, the first layer dp/2 behind the wall surface, layer k at "
    "(k - 1/2) dp. A fluid particle at the surface sees layer k while (k - 1/2) dp < the kernel "
    "support, so a wall whose particles fill the whole support needs `layers >= ceil(support / dp "
    "- 1/2)` with support = 2h (wendland, cubic) or 3h (quintic, gaussian) and h = coefh sqrt(dim) "
    "dp. With the default coefh = 1: wendland or cubic 3 layers in 2D (support 2.83 dp) and 3 in "
    "3D (3.46 dp); quintic or gaussian 4 in 2D (4.24 dp) and 5 in 3D (5.20 dp); coefh = 1.2 in 3D "
    "needs 4 with wendland (4.16 dp). Fewer layers let fluid see through a "
    "thin wall and leak; more only cost particles. The default is 3. `swell run` prints the "
    "number for the case's kernel and h.\n"
    "\n"
    "### Where the `front` gauge looks once there is an obstacle\n"
    "\n"
    "A front gauge knows nothing of bodies. At each sample it takes every fluid particle whose "
    "height above the floor is in [0, band], and reports the largest x coordinate among them plus "
    "dp/2 (solver/diagnostics.hpp surge_front). The floor is a fixed horizontal plane: the lowest "
    "fluid particle at t = 0 minus dp/2 (the initial fluid bottom), and band defaults to 2h. The "
    "front always looks along +x. So with an obstacle: water piling up or running up the "
    "obstacle's face counts while it is within the band; water on top of an obstacle higher than "
    "the band does not; water that overtops or passes around it counts again as soon as it is "
    "within the band beyond it, so the front jumps past the obstacle; a bed that rises above the "
    "band (a beach) hides the front from there on. Wall particles never count. With no fluid in "
    "the band the gauge reads nan.\n"
    "\n"
    "### What `walls: outside` builds\n"
    "\n"
    "`walls: inside` (a tank) puts `layers` rows of wall particles outside the shape: the lattice "
    "points at a distance in (0, layers dp] from its surface, less the faces listed in `open`. "
    "`walls: outside` (a structure in the flow: a caisson, a column, a breakwater) puts them "
    "inside the shape: the lattice points at a depth in (0, layers dp] beneath its surface, a "
    "shell `layers` particles thick; deeper inside the body is hollow (a body thinner than 2 "
    "layers dp is solid). Fluid lattice points inside the structure or closer than dp/2 to its "
    "surface are removed. The fluid is outside the shape, so a `fill` cannot target such a body, "
    "and gauges inside it read nan (the set-up warns).\n";

}  // namespace

std::string reference_markdown() {
  std::ostringstream o;
  o << kIntro;
  for (const Section& s : sections()) write_section(o, s);
  o << kNotes;
  return o.str();
}

namespace {

// "bodies[0].motion.height" -> "bodies.motion.height"; "bodies[].x" -> "bodies.x".
std::string strip_indices(std::string_view path) {
  std::string out;
  bool in_bracket = false;
  for (const char c : path) {
    if (c == '[') in_bracket = true;
    if (!in_bracket) out += c;
    if (c == ']') in_bracket = false;
  }
  return out;
}

}  // namespace

std::optional<std::string> reference_entry(std::string_view key_path_in) {
  const std::string want = strip_indices(key_path_in);
  if (want.empty()) return std::nullopt;
  std::ostringstream o;
  for (const Section& s : sections()) {
    if (!s.path.empty() && strip_indices(s.path) == want) {
      write_section(o, s);
      return o.str();
    }
  }
  bool found = false;
  for (const Key& k : keys()) {
    if (strip_indices(key_path(k)) != want) continue;
    const Section& s = section(k.section);
    if (!found) {
      o << "| key | for | type | default | unit | allowed | description |\n"
        << "|---|---|---|---|---|---|---|\n";
    }
    found = true;
    write_row(o, s, k);
  }
  if (!found) return std::nullopt;
  return o.str();
}

}  // namespace swell::case_schema
