#include "engine/serve/ui_address.hpp"

#include <arpa/inet.h>

#include <algorithm>
#include <cctype>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"

namespace hapscene {
namespace {

bool all_digits(std::string_view text) {
  return !text.empty() && std::all_of(text.begin(), text.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; });
}

int parse_port(std::string_view text, std::string_view whole) {
  if (!all_digits(text) || text.size() > 5 || std::stoi(std::string(text)) > 65535) {
    throw InputError("--ui: port must be a whole number in [0, 65535], got \"" + printable(whole) + "\"");
  }
  return std::stoi(std::string(text));
}

}  // namespace

bool looks_like_ui_address(std::string_view text) {
  if (all_digits(text)) return true;
  const auto colon = text.rfind(':');
  return colon != std::string_view::npos && all_digits(text.substr(colon + 1));
}

UiAddress parse_ui_address(std::string_view text) {
  UiAddress address;
  const auto colon = text.rfind(':');
  if (colon == std::string_view::npos) {
    address.port = parse_port(text, text);
    return address;
  }
  std::string host(text.substr(0, colon));
  address.port = parse_port(text.substr(colon + 1), text);
  if (host.size() >= 2 && host.front() == '[' && host.back() == ']') host = host.substr(1, host.size() - 2);
  if (host == "localhost") host = "127.0.0.1";
  unsigned char bytes[16];
  if (inet_pton(AF_INET, host.c_str(), bytes) == 1) {
    address.loopback = bytes[0] == 127;
  } else if (inet_pton(AF_INET6, host.c_str(), bytes) == 1) {
    static const unsigned char kLoopback6[16] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1};
    address.loopback = std::equal(bytes, bytes + 16, kLoopback6);
  } else {
    throw InputError("--ui: HOST must be a numeric IPv4 or IPv6 address or localhost, got \"" + printable(host) + "\"");
  }
  address.host = host;
  return address;
}

}  // namespace hapscene
