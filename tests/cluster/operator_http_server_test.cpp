// The operator console's HTTP rules without sockets
// (cluster/operator/operator_http_server.h; docs/operator.md, "JSON API" and
// "Security"): routes, the embedded page, commands and their errors, the
// token, and the Host, Origin and Content-Type rules.
#include "cluster/operator/operator_http_server.h"

#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>

namespace zenith::cluster {
namespace {

namespace http = boost::beast::http;
using Request = OperatorHttpServer::Request;
using Response = OperatorHttpServer::Response;

class OperatorHttpServerTest : public ::testing::Test {
 protected:
  OperatorHttpServer make(std::optional<SharedSecret> token = std::nullopt, std::vector<std::string> names = {}) {
    return OperatorHttpServer(io_, {"127.0.0.1", 8080, std::move(token), std::move(names)},
                              {[] {
                                 return nlohmann::json{{"state", "playing"}};
                               },
                               [this](const OperatorCommand& c, const std::string& peer) {
                                 commands_.push_back(describe(c) + " from " + peer);
                                 if (std::holds_alternative<operator_command::Pause>(c))
                                   throw std::invalid_argument("pause: no show is playing");
                                 return std::string("done");
                               },
                               [this] { return preview_; }});
  }
  static Request request(http::verb verb, const std::string& target, const std::string& body = "",
                         const std::string& content_type = "application/json") {
    Request r{verb, target, 11};
    r.set(http::field::host, "127.0.0.1:8080");
    if (!body.empty()) {
      r.set(http::field::content_type, content_type);
      r.body() = body;
      r.prepare_payload();
    }
    return r;
  }
  static nlohmann::json body_of(const Response& r) { return nlohmann::json::parse(r.body()); }

  boost::asio::io_context io_;
  std::vector<std::string> commands_;
  std::optional<std::string> preview_;
};

TEST_F(OperatorHttpServerTest, ServesThePageItsFilesAndTheStatus) {
  const OperatorHttpServer server = make();
  const Response page = server.respond(request(http::verb::get, "/"), "127.0.0.1");
  EXPECT_EQ(page.result(), http::status::ok);
  EXPECT_NE(page.body().find("zenith <span class=\"muted\">operator console"), std::string::npos);
  EXPECT_EQ(page[http::field::content_type], "text/html; charset=utf-8");
  EXPECT_NE(std::string(page["Content-Security-Policy"]).find("default-src 'self'"), std::string::npos);
  EXPECT_NE(server.respond(request(http::verb::get, "/console.js"), "x").body().find("/api/status"), std::string::npos);
  EXPECT_EQ(server.respond(request(http::verb::get, "/console.css"), "x").result(), http::status::ok);
  const Response status = server.respond(request(http::verb::get, "/api/status?t=1"), "x");
  EXPECT_EQ(status.result(), http::status::ok);
  EXPECT_EQ(body_of(status)["state"], "playing");
  EXPECT_EQ(server.respond(request(http::verb::get, "/nothing"), "x").result(), http::status::not_found);
  EXPECT_EQ(server.respond(request(http::verb::post, "/api/status", "{}"), "x").result(),
            http::status::method_not_allowed);
  EXPECT_EQ(server.respond(request(http::verb::get, "/api/command"), "x").result(), http::status::method_not_allowed);
}

TEST_F(OperatorHttpServerTest, ServesTheDomePreviewAsPngWhileThereIsOne) {
  const OperatorHttpServer server = make();
  const Response off = server.respond(request(http::verb::get, "/api/preview"), "x");
  EXPECT_EQ(off.result(), http::status::not_found);
  EXPECT_NE(body_of(off)["error"].get<std::string>().find("no dome preview: it is off"), std::string::npos);
  preview_ = std::string("\x89PNG-bytes");
  const Response on = server.respond(request(http::verb::get, "/api/preview?t=3"), "x");
  EXPECT_EQ(on.result(), http::status::ok);
  EXPECT_EQ(on[http::field::content_type], "image/png");
  EXPECT_EQ(on[http::field::cache_control], "no-store");
  EXPECT_EQ(on.body(), "\x89PNG-bytes");
  EXPECT_EQ(server.respond(request(http::verb::post, "/api/preview", "{}"), "x").result(),
            http::status::method_not_allowed);
  // The page shows it from a blob: URL (fetched with the token), which its policy allows.
  EXPECT_NE(std::string(server.respond(request(http::verb::get, "/"), "x")["Content-Security-Policy"])
                .find("img-src 'self' data: blob:"),
            std::string::npos);
}

TEST_F(OperatorHttpServerTest, CommandsAreAnsweredWithTheReplyOrA400NamingTheError) {
  const OperatorHttpServer server = make();
  const Response ok =
      server.respond(request(http::verb::post, "/api/command", R"({"command": "seek", "seconds": 2})"), "127.0.0.1");
  EXPECT_EQ(ok.result(), http::status::ok);
  EXPECT_EQ(body_of(ok), (nlohmann::json{{"ok", true}, {"reply", "done"}}));
  EXPECT_EQ(commands_, std::vector<std::string>{"seek 2.0 from http 127.0.0.1"});
  const Response bad =
      server.respond(request(http::verb::post, "/api/command", R"({"command": "rate", "rate": 99})"), "x");
  EXPECT_EQ(bad.result(), http::status::bad_request);
  EXPECT_EQ(body_of(bad)["error"], "command: /rate = 99: must be in [-16, 16]");
  const Response refused = server.respond(request(http::verb::post, "/api/command", R"({"command": "pause"})"), "x");
  EXPECT_EQ(refused.result(), http::status::bad_request);
  EXPECT_EQ(body_of(refused)["error"], "pause: no show is playing");
  EXPECT_EQ(commands_.size(), 2u) << "the malformed rate never reached the master";
}

TEST_F(OperatorHttpServerTest, RefusesCrossSiteAndRebindingRequests) {
  const OperatorHttpServer server = make();
  // A page elsewhere can send text/plain without asking the browser first: refused.
  EXPECT_EQ(
      server.respond(request(http::verb::post, "/api/command", R"({"command": "quit"})", "text/plain"), "x").result(),
      http::status::unsupported_media_type);
  Request foreign = request(http::verb::post, "/api/command", R"({"command": "quit"})");
  foreign.set(http::field::origin, "http://evil.example");
  EXPECT_EQ(server.respond(foreign, "x").result(), http::status::forbidden);
  Request same = request(http::verb::post, "/api/command", R"({"command": "play"})");
  same.set(http::field::origin, "http://127.0.0.1:8080");
  EXPECT_EQ(server.respond(same, "x").result(), http::status::ok);
  Request rebound = request(http::verb::get, "/api/status");
  rebound.set(http::field::host, "attacker.example:8080");
  EXPECT_EQ(server.respond(rebound, "x").result(), http::status::forbidden);
  Request named = request(http::verb::get, "/api/status");
  named.set(http::field::host, "localhost:8080");
  EXPECT_EQ(server.respond(named, "x").result(), http::status::ok);
  EXPECT_EQ(commands_, std::vector<std::string>{"play from http x"});
}

TEST_F(OperatorHttpServerTest, WithATokenEveryApiRequestMustCarryIt) {
  const OperatorHttpServer server =
      make(SharedSecret(std::vector<std::uint8_t>(20, 'k'), "test"), {"dome-master.local"});
  const std::string token(20, 'k');
  // The page holds no secret: served without the token.
  EXPECT_EQ(server.respond(request(http::verb::get, "/"), "x").result(), http::status::ok);
  EXPECT_EQ(server.respond(request(http::verb::get, "/api/preview"), "x").result(), http::status::unauthorized);
  const Response missing = server.respond(request(http::verb::get, "/api/status"), "x");
  EXPECT_EQ(missing.result(), http::status::unauthorized);
  EXPECT_EQ(missing[http::field::www_authenticate], "Bearer realm=\"zenith operator console\"");
  Request wrong = request(http::verb::post, "/api/command", R"({"command": "quit"})");
  wrong.set(http::field::authorization, "Bearer " + std::string(20, 'j'));
  EXPECT_EQ(server.respond(wrong, "x").result(), http::status::unauthorized);
  EXPECT_TRUE(commands_.empty());
  Request right = request(http::verb::post, "/api/command", R"({"command": "quit"})");
  right.set(http::field::authorization, "Bearer " + token);
  right.set(http::field::host, "dome-master.local:8080");  // a configured name (--operator-name) with a token
  EXPECT_EQ(server.respond(right, "x").result(), http::status::ok);
  EXPECT_EQ(commands_, std::vector<std::string>{"quit from http x"});
}

// DNS rebinding: "127.evil.example" resolved to 127.0.0.1 by its owner's
// DNS once passed as loopback, with a matching Origin: a page there had the
// console. Only the loopback literals with the console's own port pass now.
TEST_F(OperatorHttpServerTest, RefusesDnsRebindingToLoopbackLookAlikesAndOtherPorts) {
  const OperatorHttpServer server = make();
  const auto status_with_host = [&](const std::string& host, bool command = false) {
    Request r = command ? request(http::verb::post, "/api/command", R"({"command": "exposure", "exposure": 77})")
                        : request(http::verb::get, "/api/status");
    r.set(http::field::host, host);
    r.set(http::field::origin, "http://" + host);
    return server.respond(r, "127.0.0.1").result();
  };
  EXPECT_EQ(status_with_host("127.evil.example:8080", true), http::status::forbidden);
  EXPECT_EQ(status_with_host("127.0.0.1.evil.example:8080"), http::status::forbidden);
  EXPECT_EQ(status_with_host("127.0.0.2:8080"), http::status::forbidden) << "exactly the literals";
  EXPECT_EQ(status_with_host("127.0.0.1:9999"), http::status::forbidden) << "another port: another service's page";
  EXPECT_EQ(status_with_host("127.0.0.1"), http::status::forbidden) << "no port is port 80";
  EXPECT_EQ(status_with_host("127.0.0.1:8080x"), http::status::forbidden);
  EXPECT_EQ(status_with_host("localhost:08080"), http::status::ok) << "the same port, written with a zero";
  EXPECT_EQ(status_with_host("[::1]:8080"), http::status::ok);
  EXPECT_EQ(status_with_host("127.0.0.1:8080", true), http::status::ok);
  EXPECT_EQ(commands_, std::vector<std::string>{"exposure 77.0 from http 127.0.0.1"});
  // A refusal quotes the Host escaped: no forged log lines.
  Request forged = request(http::verb::get, "/api/status");
  forged.set(http::field::host, "x\x1b[31m");
  EXPECT_NE(server.respond(forged, "x").body().find("x\\\\x1b[31m"), std::string::npos)
      << server.respond(forged, "x").body();

  // With a token: the literals, IP addresses (no DNS answer can rebind them) and the configured names.
  const OperatorHttpServer tokened = make(SharedSecret(std::vector<std::uint8_t>(20, 'k'), "test"), {"dome.local"});
  const auto with_token = [&](const std::string& host) {
    Request r = request(http::verb::get, "/api/status");
    r.set(http::field::host, host);
    r.set(http::field::authorization, "Bearer " + std::string(20, 'k'));
    return tokened.respond(r, "x").result();
  };
  EXPECT_EQ(with_token("10.0.0.5:8080"), http::status::ok);
  EXPECT_EQ(with_token("[fe80::1]:8080"), http::status::ok);
  EXPECT_EQ(with_token("dome.local:8080"), http::status::ok);
  EXPECT_EQ(with_token("127.evil.example:8080"), http::status::forbidden);
  EXPECT_EQ(with_token("dome.local.evil.example:8080"), http::status::forbidden);
  EXPECT_EQ(with_token("dome.local:8081"), http::status::forbidden);
}

TEST_F(OperatorHttpServerTest, RefusesToListenBeyondLoopbackWithoutAToken) {
  OperatorHttpServer server(io_, {"0.0.0.0", 0, std::nullopt, {}}, {});
  try {
    server.start();
    FAIL() << "started without a token";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("needs an operator token"), std::string::npos) << e.what();
  }
  OperatorHttpServer named(io_, {"localhost", 0, std::nullopt, {}}, {});
  EXPECT_THROW(named.start(), std::runtime_error);  // numeric addresses only
  OperatorHttpServer loopback(io_, {"127.0.0.1", 0, std::nullopt, {}}, {});
  loopback.start();
  EXPECT_GT(loopback.port(), 0);
  EXPECT_EQ(loopback.url(), "http://127.0.0.1:" + std::to_string(loopback.port()) + "/");
  loopback.close();
}

}  // namespace
}  // namespace zenith::cluster
