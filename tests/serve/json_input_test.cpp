// Checked reading of request bodies (app/serve/json_input.h, solve_request_json.h): every refusal is an
// HttpError with the status the API documents and a message naming the field, the position or the byte.
#include "../../app/serve/http_error.h" // the tool's sources: tests/ is on the include path, app/ is not
#include "../../app/serve/json_input.h"
#include "../../app/serve/solve_request_json.h"
#include "serve_test_meshes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>

namespace {

using iarap::serve::HttpError;
using iarap::test::contains;
using nlohmann::json;
namespace serve = iarap::serve;

// The HttpError f throws: its status and message ({0, ""} when it throws none).
std::pair<int, std::string> refusal(const std::function<void()>& f) {
  try {
    f();
  } catch (const HttpError& e) {
    return {e.status(), e.what()};
  }
  return {0, ""};
}

// The message of the InputError (any kind) f throws, "" when none.
std::string input_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const iarap::InputError& e) {
    return e.what();
  }
  return "";
}

} // namespace

TEST(ServeJsonInput, MalformedJsonNamesTheByte) {
  const auto [status, message] = refusal([] { serve::parse_json_object("{\"fixed\": [1, 2", 1024); });
  EXPECT_EQ(status, 400);
  EXPECT_TRUE(contains(message, "malformed JSON at byte 16")) << message; // 1-based: the end of the text
  // JSON has no NaN; a literal is a syntax error at its byte.
  const auto [nan_status, nan_message] =
      refusal([] { serve::parse_json_object("{\"tolerance\": NaN}", 1024); });
  EXPECT_EQ(nan_status, 400);
  EXPECT_TRUE(contains(nan_message, "malformed JSON at byte 15")) << nan_message;
  // A number past the double range is refused by the parser, which names it.
  const auto [big_status, big_message] =
      refusal([] { serve::parse_json_object("{\"gravity\": [0, 1e999, 0]}", 1024); });
  EXPECT_EQ(big_status, 400);
  EXPECT_TRUE(contains(big_message, "1e999")) << big_message;
}

TEST(ServeJsonInput, BodyMustBeOneObjectWithinTheLimits) {
  EXPECT_EQ(refusal([] { serve::parse_json_object("[1, 2]", 1024); }),
            std::make_pair(400, std::string("request body must be a JSON object, got array")));
  const auto [too_large, message] = refusal([] { serve::parse_json_object(std::string(2000, ' '), 1024); });
  EXPECT_EQ(too_large, 413);
  EXPECT_TRUE(contains(message, "2000 bytes")) << message;
  const std::string deep = std::string(40, '[') + std::string(40, ']');
  const auto [deep_status, deep_message] = refusal([&] { serve::parse_json_object(deep, 1024); });
  EXPECT_EQ(deep_status, 400);
  EXPECT_TRUE(contains(deep_message, "deeper than 32")) << deep_message;
  EXPECT_EQ(serve::parse_json_object("{\"a\": \"[[[[\"}", 1024).at("a"), "[[[["); // brackets in strings
}

TEST(ServeJsonInput, IntegerArraysNameThePosition) {
  const json body = json::parse(R"({"fixed": [1, "2"], "handle": [0, 1.5], "n": 3, "big": [3000000000]})");
  EXPECT_EQ(refusal([&] { serve::integer_array_field(body, "fixed"); }).second,
            "fixed[1] must be an integer vertex index, got \"2\"");
  EXPECT_EQ(refusal([&] { serve::integer_array_field(body, "handle"); }).second,
            "handle[1] must be an integer vertex index, got 1.5");
  EXPECT_EQ(refusal([&] { serve::integer_array_field(body, "n"); }).second, "n must be an array, got number");
  EXPECT_EQ(refusal([&] { serve::integer_array_field(body, "big"); }).second,
            "big[0] = 3000000000 is too large");
  EXPECT_EQ(serve::integer_array_field(body, "absent").size(), 0);
  EXPECT_EQ(serve::integer_array_field(json::parse(R"({"a": [4, -1]})"), "a"), Eigen::Vector2i(4, -1));
}

TEST(ServeJsonInput, NonFiniteNumbersAreNamed) {
  json body;
  body["gravity"] = {0.0, std::numeric_limits<double>::quiet_NaN(), 0.0};
  body["forces"] = {1.0, 2.0, std::numeric_limits<double>::infinity()};
  body["transform"] = {1.0, "x"};
  EXPECT_EQ(refusal([&] { serve::number_array_field(body, "gravity"); }),
            std::make_pair(400, std::string("gravity[1] is not finite")));
  EXPECT_EQ(refusal([&] { serve::number_array_field(body, "forces"); }).second, "forces[2] is not finite");
  EXPECT_EQ(refusal([&] { serve::number_array_field(body, "transform"); }).second,
            "transform[1] must be a number, got \"x\"");
}

TEST(ServeJsonInput, ScalarFieldsNameTheirTypeAndRange) {
  const json body = json::parse(R"({"revision": 0, "method": 3, "refine": "yes", "iteratons": 5})");
  EXPECT_EQ(refusal([&] { serve::integer_field(body, "revision", 0, 1, 10); }).second,
            "revision must be an integer in 1..10, got 0");
  EXPECT_EQ(refusal([&] { serve::string_field(body, "method", "iarap"); }).second,
            "method must be a string, got 3");
  EXPECT_EQ(refusal([&] { serve::bool_field(body, "refine", false); }).second,
            "refine must be true or false, got \"yes\"");
  const auto [status, message] = refusal([&] {
    serve::require_known_fields(body, {"revision", "method", "refine"});
  });
  EXPECT_EQ(status, 400);
  EXPECT_TRUE(contains(message, "unknown field \"iteratons\"")) << message;
  EXPECT_EQ(serve::integer_field(body, "absent", 7, 1, 10), 7);
}

TEST(ServeJsonInput, NumberFieldsAreFiniteNumbers) {
  json body = json::parse(R"({"padding": 2.5, "max_angle": "60", "flag": true})");
  body["huge"] = std::numeric_limits<double>::infinity(); // a parsed body cannot hold one: a caller's can
  EXPECT_EQ(serve::number_field(body, "padding", 0), 2.5);
  EXPECT_EQ(serve::number_field(body, "absent", 7), 7);
  EXPECT_EQ(refusal([&] { serve::number_field(body, "max_angle", 0); }).second,
            "max_angle must be a finite number, got \"60\"");
  EXPECT_EQ(refusal([&] { serve::number_field(body, "flag", 0); }).second,
            "flag must be a finite number, got true");
  const auto [status, message] = refusal([&] { serve::number_field(body, "huge", 0); });
  EXPECT_EQ(status, 400);
  EXPECT_TRUE(contains(message, "huge must be a finite number")) << message;
}

TEST(ServeJsonInput, SolveRequestFieldsAreChecked) {
  const auto solve_error = [](const std::string& text) {
    return input_error([&] { serve::parse_solve_request(json::parse(text), 1000); });
  };
  EXPECT_TRUE(contains(solve_error(R"({"iterations": 5000})"), "iterations must be an integer in [1, 1000]"));
  EXPECT_TRUE(contains(solve_error(R"({"transform": [1, 0, 0]})"), "transform has 3 numbers; expected 16"));
  EXPECT_TRUE(contains(solve_error(R"({"handle_targets": [1, 2]})"), "a multiple of 3"));
  EXPECT_TRUE(contains(solve_error(R"({"gravity": [0, -9.8]})"), "gravity has 2 numbers; expected 3"));
  EXPECT_TRUE(contains(solve_error(R"({"density": -1})"), "density must be a finite number > 0"));
  EXPECT_TRUE(contains(solve_error(R"({"tolerance": "small"})"), "tolerance"));
  EXPECT_TRUE(contains(solve_error(R"({"method": "rigid"})"), "rigid"));
  EXPECT_TRUE(contains(solve_error(R"({"refine_accelerator": "fast"})"), "refine_accelerator must be"));
  EXPECT_TRUE(contains(solve_error(R"({"trasform": []})"), "unknown field \"trasform\""));

  const serve::SolveRequest request =
      serve::parse_solve_request(json::parse(R"({"method": "arap", "iterations": 7, "refine": true,
                      "transform": [1,0,0,0, 0,1,0,0, 0,0,1,0, 2,3,4,1]})"),
                                 1000);
  EXPECT_EQ(request.method, iarap::ArapMethod::Arap);
  EXPECT_EQ(request.solve.max_iterations, 7);
  EXPECT_EQ(request.refine_iterations, 1000);
  ASSERT_TRUE(request.transform.has_value());
  EXPECT_EQ(request.transform->col(3), Eigen::Vector4d(2, 3, 4, 1)); // column-major, as the page sends it
  EXPECT_TRUE(contains(input_error([] {
                         serve::parse_target_request(json::parse(R"({"method": "arap", "iterations": 3})"),
                                                     1000);
                       }),
                       "unknown field \"iterations\""));
}
