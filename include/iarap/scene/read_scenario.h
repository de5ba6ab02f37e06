// Reader of scenario files (JSON), the format documented in README.md ("Scenario files").
//
// {
//   "description": "text",                              (optional)
//   "fixed":   [ REGION, ... ],                          (optional; union)
//   "handles": [ { "name": "text",                       (optional)
//                  "vertices": [ REGION, ... ],          (union)
//                  "translate": [x, y, z]  or  "translate_relative": [x, y, z]  (bbox diagonals),
//                  "rotate": { "axis": [x, y, z] or "x"|"y"|"z", "degrees": a,
//                              "center": [x, y, z], "center_relative": [u, v, w] } }, ... ]
// }
// REGION: [i, j, ...] | {"indices": [...]} | {"bottom": f, "axis": "y"} | {"top": f, "axis": "y"}
//       | {"box": {"min": [..], "max": [..]}} | {"box": {"min": .., "max": .., "relative": true}}
//       | {"sphere": {"center": [..], "radius": r}} (also with "relative": true)
#pragma once
#include "iarap/scene/scenario.h"

#include <string>

namespace iarap {

// Parses scenario JSON text; source names the input in messages. Throws InputError with the
// source and the JSON path of the offending value ("scene.json: handles[0].rotate.axis: ...") on a
// syntax error (with line and column), an unknown key, a wrong type or a value out of range.
Scenario parse_scenario(const std::string& text, const std::string& source);

// Reads and parses the scenario file at path. Throws InputError when it cannot be read.
Scenario read_scenario(const std::string& path);

} // namespace iarap
