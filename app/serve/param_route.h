// The viewer's UV tab: POST /api/param flattens the session's rest mesh and answers a binary frame, the
// report as its JSON header. A topological disk is one chart (arap_parameterize): the map as "uv" (float32
// #V x 2, row-major). Any other mesh is an atlas (uv_atlas): "corner_uv" (float32 #F x 3 x 2, corner k of
// face f at 6 f + 2 k) and "chart" (int32 #F, -1 for a face without an area).
#pragma once
#include "session.h"

#include "iarap/param/param_options.h"
#include "iarap/param/uv_atlas.h"

#include <nlohmann/json.hpp>
#include <string>

namespace iarap::serve {

struct ParamRequest {
  ParamOptions disk;      // the one chart of a disk
  AtlasOptions atlas;     // any other mesh; atlas.param: disk's options, tolerance 1e-4 unless given
  bool one_chart = false; // "charts": "one": a mesh that is not a disk is refused (422)
};

// body: {"energy": "triangle" | "arap" | "iarap", "boundary": "free" | "circle", "init": "lscm" | "tutte" |
// "harmonic", "allow_flips": bool, "charts": "auto" | "one", the atlas's "texture_size" (16..16384),
// "padding" (texels, [0, texture_size / 2)), "max_angle" (degrees, (0, 180]), "target_distortion" (> 0),
// "min_chart_faces" (>= 1), and the solve options of solve_option_json.h ("iterations":
// 0..max_iterations)}, every field optional (the defaults of `iarap param`). Throws InputError or HttpError
// (400) naming the field for an unknown field or a bad value; checked before the session is asked for its
// mesh.
ParamRequest parse_param_request(const nlohmann::json& body, int max_iterations);

// The frame of the rest mesh's map: one chart for a disk (or "charts": "one"), an atlas otherwise. Throws
// TopologyError (422) for a mesh that is not a disk with "charts": "one" (the message says what it has) or
// that is not an oriented manifold (what check_mesh reports), SolverError (422).
std::string param_frame(const MeshSnapshot& rest, const ParamRequest& request);

} // namespace iarap::serve
