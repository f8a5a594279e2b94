#include "engine/serve/live_hand.hpp"

#include <httplib.h>

#include <cctype>
#include <cmath>

#include <nlohmann/json.hpp>

#include "engine/base/object_reader.hpp"
#include "engine/serve/live_requests.hpp"

namespace hapscene {

using json = nlohmann::json;

template <int N>
void move_hand(HandPointerOf<N>* pointer, const std::string& request_body, LiveDocumentOf<N>& document,
               httplib::Response& res) {
  if (pointer == nullptr) {
    error_response(res, 409, "this device's hand is not the page's to move (only --device sim's is): on a real device it is yours");
    return;
  }
  std::string form = "{\"x_m\": X";
  for (int i = 1; i < N; ++i) form += std::string(", \"") + kAxisNames[i] + "_m\": " + static_cast<char>(std::toupper(kAxisNames[i][0]));
  form += "} or {\"release\": true}";
  json body;
  try {
    body = json::parse(request_body);
  } catch (const json::exception&) {
    error_response(res, 400, "request: expected a JSON object " + form);
    return;
  }
  if (!body.is_object()) {
    error_response(res, 400, "request: expected a JSON object " + form);
    return;
  }
  if (body.contains("release")) {
    if (body.size() != 1 || body["release"] != true) {
      error_response(res, 400, "request: expected {\"release\": true} alone");
      return;
    }
    pointer->release();
    res.set_content(json{{"hand", "released"}}.dump(), "application/json");
    return;
  }
  if (body.size() != static_cast<std::size_t>(N)) {
    error_response(res, 400, "request: expected a JSON object " + form);
    return;
  }
  const auto [workspace_min_m, workspace_max_m] = document.workspace_m();  // what the page shows
  Axes<N> x_m{};
  json shown = json::object();
  for (int i = 0; i < N; ++i) {
    const std::string key = std::string(kAxisNames[i]) + "_m";
    const auto found = body.find(key);
    if (found == body.end() || !found->is_number() || !std::isfinite(found->get<double>())) {
      error_response(res, 400, "request: \"" + key + "\" must be a finite number of metres (" + form + ")");
      return;
    }
    const double value_m = found->get<double>();
    const double low_m = component(workspace_min_m, i);
    const double high_m = component(workspace_max_m, i);
    if (value_m < low_m || value_m > high_m) {
      error_response(res, 400, key + ": " + format_number(value_m) + " m is outside the workspace [" +
                                   format_number(low_m) + ", " + format_number(high_m) + "] m");
      return;
    }
    set_component(x_m, i, value_m);
    shown[key] = value_m;
  }
  pointer->take(x_m);
  shown["hand"] = "pointer";
  res.set_content(shown.dump(), "application/json");
}

#define HAPSCENE_MOVE_HAND(N) \
  template void move_hand<N>(HandPointerOf<N>*, const std::string&, LiveDocumentOf<N>&, httplib::Response&);
HAPSCENE_FOR_EACH_AXES(HAPSCENE_MOVE_HAND)
#undef HAPSCENE_MOVE_HAND

}  // namespace hapscene
