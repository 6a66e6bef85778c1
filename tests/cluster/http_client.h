#pragma once
// A blocking HTTP/1.1 client for the tests (Boost.Beast): the operator
// console's API (docs/operator.md) and a WebDriver (webdriver.h), on
// 127.0.0.1.
#include <sys/socket.h>
#include <sys/time.h>

#include <cstdint>
#include <string>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/http.hpp>
#include <nlohmann/json.hpp>

namespace zenith::cluster::test {

struct HttpReply {
  int status = 0;  ///< 0: no connection, or no answer within the timeout
  std::string body;
  /// The body as JSON (a discarded value when it is not JSON).
  nlohmann::json json() const { return nlohmann::json::parse(body, nullptr, false); }
};

/// One request to 127.0.0.1:`port`; waits at most `timeout_s` for the answer.
inline HttpReply http_request(int port, boost::beast::http::verb verb, const std::string& target,
                              const std::string& body = "", const std::string& content_type = "application/json",
                              long timeout_s = 30) {
  namespace http = boost::beast::http;
  try {
    boost::asio::io_context io;
    boost::asio::ip::tcp::socket socket(io);
    socket.connect({boost::asio::ip::make_address("127.0.0.1"), static_cast<std::uint16_t>(port)});
    const timeval timeout{timeout_s, 0};
    setsockopt(socket.native_handle(), SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    http::request<http::string_body> request{verb, target, 11};
    request.set(http::field::host, "127.0.0.1:" + std::to_string(port));
    if (!body.empty()) {
      request.set(http::field::content_type, content_type);
      request.body() = body;
    }
    request.prepare_payload();
    http::write(socket, request);
    boost::beast::flat_buffer buffer;
    http::response_parser<http::string_body> parser;
    parser.body_limit(64 * 1024 * 1024);  // screenshots
    http::read(socket, buffer, parser);
    return {static_cast<int>(parser.get().result_int()), parser.get().body()};
  } catch (const std::exception&) {
    return {};
  }
}

}  // namespace zenith::cluster::test
