// Scenario files are JSON, parsed with nlohmann-json; this file maps the JSON onto Scenario and
// reports every mistake with the JSON path of the value at fault.
#include "iarap/scene/read_scenario.h"

#include "iarap/core/errors.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <limits>
#include <sstream>

namespace iarap {
namespace {

using nlohmann::json;

// A JSON value with the path that reached it, so errors can name it.
struct Node {
  const json& value;
  std::string path; // "source: handles[0].rotate"

  // A missing key or item is an input error that names it, never json's out_of_range.
  Node key(const std::string& name) const {
    if (!value.is_object() || !value.contains(name)) fail("missing key '" + name + "'");
    return {value.at(name), path + "." + name};
  }
  Node item(std::size_t i) const {
    if (!value.is_array() || i >= value.size()) fail("missing item [" + std::to_string(i) + "]");
    return {value.at(i), path + "[" + std::to_string(i) + "]"};
  }
  [[noreturn]] void fail(const std::string& what) const { throw InputError(path + ": " + what); }

  void require_object(std::initializer_list<const char*> allowed) const {
    if (!value.is_object()) fail("expected an object, found " + std::string(value.type_name()));
    for (const auto& [name, unused] : value.items()) {
      bool known = false;
      std::string list;
      for (const char* a : allowed) {
        known = known || name == a;
        list += std::string(list.empty() ? "" : ", ") + a;
      }
      if (!known) fail("unknown key '" + name + "' (allowed: " + list + ")");
    }
  }
  bool has(const char* name) const { return value.contains(name); }

  double number() const {
    if (!value.is_number()) fail("expected a number, found " + std::string(value.type_name()));
    const double x = value.get<double>();
    if (!std::isfinite(x)) fail("number is not finite");
    return x;
  }
  std::string string() const {
    if (!value.is_string()) fail("expected a string, found " + std::string(value.type_name()));
    return value.get<std::string>();
  }
  bool boolean() const {
    if (!value.is_boolean()) fail("expected true or false, found " + std::string(value.type_name()));
    return value.get<bool>();
  }
  // [x, y, z]; with in_plane, [x, y] too: a point or offset in the plane z = 0 (a planar scene).
  Eigen::Vector3d vector3(bool in_plane = true) const {
    if (!in_plane && (!value.is_array() || value.size() != 3)) fail("expected an array of 3 numbers");
    if (!value.is_array() || (value.size() != 3 && value.size() != 2))
      fail("expected an array of 3 numbers (or 2 in the plane z = 0)");
    return {item(0).number(), item(1).number(), value.size() == 3 ? item(2).number() : 0.0};
  }
  int index() const {
    if (!value.is_number_integer()) fail("expected a vertex index (integer), found " + value.dump());
    const auto i = value.get<long long>();
    if (i < 0 || i > std::numeric_limits<int>::max())
      fail("vertex index " + std::to_string(i) + " out of range");
    return static_cast<int>(i);
  }
  void for_each(const std::function<void(const Node&)>& visit) const {
    if (!value.is_array()) fail("expected an array, found " + std::string(value.type_name()));
    for (std::size_t i = 0; i < value.size(); ++i) visit(item(i));
  }
};

int parse_axis(const Node& node) {
  const std::string name = node.string();
  if (name == "x") return 0;
  if (name == "y") return 1;
  if (name == "z") return 2;
  node.fail("axis must be \"x\", \"y\" or \"z\", found \"" + name + "\"");
}

Region parse_region(const Node& node) {
  Region region;
  region.path = node.path;
  if (node.value.is_array()) { // shorthand: a plain index list
    node.for_each([&](const Node& i) { region.indices.push_back(i.index()); });
    return region;
  }
  if (!node.value.is_object()) node.fail("expected an index list or a region object");
  if (node.has("indices")) {
    node.require_object({"indices"});
    node.key("indices").for_each([&](const Node& i) { region.indices.push_back(i.index()); });
  } else if (node.has("bottom") || node.has("top")) {
    const bool bottom = node.has("bottom");
    node.require_object({bottom ? "bottom" : "top", "axis"});
    region.kind = bottom ? RegionKind::Bottom : RegionKind::Top;
    const Node fraction = node.key(bottom ? "bottom" : "top");
    region.fraction = fraction.number();
    if (!(region.fraction > 0 && region.fraction <= 1)) fraction.fail("fraction must be in (0, 1]");
    region.axis = node.has("axis") ? parse_axis(node.key("axis")) : 1;
  } else if (node.has("box")) {
    node.require_object({"box"});
    const Node box = node.key("box");
    box.require_object({"min", "max", "relative"});
    region.kind = RegionKind::Box;
    region.lo = box.key("min").vector3();
    region.hi = box.key("max").vector3();
    region.relative = box.has("relative") && box.key("relative").boolean();
    if (!(region.lo.array() <= region.hi.array()).all()) box.fail("min exceeds max on some axis");
  } else if (node.has("sphere")) {
    node.require_object({"sphere"});
    const Node sphere = node.key("sphere");
    sphere.require_object({"center", "radius", "relative"});
    region.kind = RegionKind::Sphere;
    region.center = sphere.key("center").vector3();
    region.radius = sphere.key("radius").number();
    region.relative = sphere.has("relative") && sphere.key("relative").boolean();
    if (region.radius < 0) sphere.key("radius").fail("radius must be >= 0");
  } else {
    node.fail("a region needs one of \"indices\", \"bottom\", \"top\", \"box\", \"sphere\"");
  }
  return region;
}

// "fixed" and "vertices" take one region or an array of regions. An array of integers is one
// index-list region, so an array whose first element is an object or an array is a list of regions.
std::vector<Region> parse_regions(const Node& node) {
  std::vector<Region> regions;
  const bool list_of_regions =
      node.value.is_array() && !node.value.empty() && (node.value[0].is_object() || node.value[0].is_array());
  if (list_of_regions) {
    node.for_each([&](const Node& r) { regions.push_back(parse_region(r)); });
  } else {
    regions.push_back(parse_region(node));
  }
  return regions;
}

Handle parse_handle(const Node& node) {
  node.require_object({"name", "vertices", "translate", "translate_relative", "rotate", "weight"});
  Handle handle;
  handle.path = node.path;
  if (node.has("name")) handle.name = node.key("name").string();
  if (!node.has("vertices")) node.fail("a handle needs \"vertices\"");
  handle.vertices = parse_regions(node.key("vertices"));
  if (node.has("weight")) { // a soft handle
    handle.weight = node.key("weight").number();
    if (!(handle.weight > 0)) node.key("weight").fail("a soft handle's weight must be > 0");
  }
  if (node.has("translate") && node.has("translate_relative")) {
    node.fail("give either \"translate\" or \"translate_relative\", not both");
  }
  if (node.has("translate")) handle.translation = node.key("translate").vector3();
  if (node.has("translate_relative")) {
    handle.translation = node.key("translate_relative").vector3();
    handle.translation_relative = true;
  }
  if (node.has("rotate")) {
    const Node rotate = node.key("rotate");
    rotate.require_object({"axis", "degrees", "center", "center_relative"});
    if (!rotate.has("axis") || !rotate.has("degrees"))
      rotate.fail("a rotation needs \"axis\" and \"degrees\"");
    const Node axis = rotate.key("axis");
    if (axis.value.is_string()) {
      handle.rotation_axis = Eigen::Vector3d::Unit(parse_axis(axis));
    } else {
      handle.rotation_axis = axis.vector3(false); // an axis in the plane would turn it over
      if (handle.rotation_axis.norm() == 0) axis.fail("rotation axis must be non-zero");
    }
    handle.rotation_degrees = rotate.key("degrees").number();
    if (rotate.has("center") && rotate.has("center_relative")) {
      rotate.fail("give either \"center\" or \"center_relative\", not both");
    }
    if (rotate.has("center")) handle.rotation_center = rotate.key("center").vector3();
    if (rotate.has("center_relative")) {
      handle.rotation_center = rotate.key("center_relative").vector3();
      handle.rotation_center_relative = true;
    }
  }
  return handle;
}

} // namespace

Scenario parse_scenario(const std::string& text, const std::string& source) {
  json document;
  try {
    document = json::parse(text);
  } catch (const json::parse_error& e) {
    // e.what() reads "[json.exception.parse_error.101] parse error at line 3, column 5: ..."
    const std::string message = e.what();
    const auto at = message.find("parse error");
    throw InputError(source + ": " + (at == std::string::npos ? message : message.substr(at)));
  } catch (const json::out_of_range& e) {
    // e.what() reads "[json.exception.out_of_range.406] number overflow parsing '1e400'", without a place.
    const std::string message = e.what();
    const auto open = message.find('\'');
    const auto close = open == std::string::npos ? open : message.find('\'', open + 1);
    if (close == std::string::npos) throw InputError(source + ": " + message);
    const std::string number = message.substr(open + 1, close - open - 1);
    const auto at = text.find(number);
    const std::string line =
        at == std::string::npos
            ? ""
            : ":" + std::to_string(
                        1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
    throw InputError(source + line + ": number " + number +
                     " is beyond the range of a double (about 1.8e308); every number must be finite");
  }
  const Node root{document, source + ": $"};
  root.require_object({"description", "fixed", "handles"});
  Scenario scenario;
  scenario.source = source;
  if (root.has("description")) scenario.description = root.key("description").string();
  if (root.has("fixed")) scenario.fixed = parse_regions(root.key("fixed"));
  if (root.has("handles")) {
    root.key("handles").for_each([&](const Node& h) { scenario.handles.push_back(parse_handle(h)); });
  }
  if (scenario.fixed.empty() && scenario.handles.empty()) {
    root.fail("a scenario needs \"fixed\" and/or \"handles\"");
  }
  return scenario;
}

Scenario read_scenario(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open scenario file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path + ": read error");
  return parse_scenario(text.str(), path);
}

} // namespace iarap
