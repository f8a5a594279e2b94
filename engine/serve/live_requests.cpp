#include "engine/serve/live_requests.hpp"

#include <random>

#include <nlohmann/json.hpp>

#include "engine/serve/connection_gate.hpp"

namespace hapscene {

std::string new_token() {
  std::random_device source;
  std::string token;
  static const char* kHex = "0123456789abcdef";
  for (int i = 0; i < 8; ++i) {
    const unsigned int word = source();
    for (int k = 0; k < 4; ++k) token.push_back(kHex[(word >> (4 * k)) & 0xf]);
  }
  return token;
}

bool same_token(const std::string& given, const std::string& token) {
  if (given.size() != token.size()) return false;
  unsigned char difference = 0;
  for (std::size_t i = 0; i < token.size(); ++i) difference |= static_cast<unsigned char>(given[i] ^ token[i]);
  return difference == 0;
}

void error_response(httplib::Response& res, int status, const std::string& message) {
  res.status = status;
  res.set_content(nlohmann::json{{"error", message}}.dump(), "application/json");
}

bool read_body(const httplib::Request& req, httplib::Response& res, const httplib::ContentReader& reader,
               std::string* body) {
  if (!req.has_header("Content-Length") && !req.has_header("Transfer-Encoding")) return true;
  bool too_large = false;
  const bool read = reader([&](const char* data, std::size_t length) {
    if (body->size() + length > kMaxRequestBodyBytes) {
      too_large = true;
      return false;
    }
    body->append(data, length);
    return true;
  });
  if (read && !too_large) return true;
  GatedServer::close_after_response();
  if (too_large) {
    error_response(res, 413, "request body: larger than " + std::to_string(kMaxRequestBodyBytes) + " bytes");
  } else {
    error_response(res, 400, "request body: could not be read whole");
  }
  return false;
}

}  // namespace hapscene
