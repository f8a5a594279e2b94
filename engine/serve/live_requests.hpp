#pragma once
// What every request of the live view goes through: the session token (made from the
// system's random source, compared in constant time), a bounded body, and JSON errors.
#include <cstddef>
#include <string>

#include <httplib.h>

namespace hapscene {

// The largest request body taken, however it is sent (a parameter change is ~100 bytes).
inline constexpr std::size_t kMaxRequestBodyBytes = std::size_t{1} << 16;

// 128 random bits as hex, from the system's random source.
std::string new_token();

// Compares without an early exit, so the time taken says nothing about the token.
bool same_token(const std::string& given, const std::string& token);

// Sets `res` to `status` with {"error": message}.
void error_response(httplib::Response& res, int status, const std::string& message);

// Reads a request's body into `body`, at most kMaxRequestBodyBytes however it is sent
// (Content-Length, chunked, or until the connection ends): false, with the response
// set (413 or 400) and the connection to be closed, when it is larger or cannot be read.
// A request with neither a length nor chunks (`curl -X POST`) has an empty body.
bool read_body(const httplib::Request& req, httplib::Response& res, const httplib::ContentReader& reader,
               std::string* body);

}  // namespace hapscene
