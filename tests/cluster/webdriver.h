#pragma once
// A minimal W3C WebDriver client for the tests: Debian's chromium driven
// headless by its chromedriver (scripts/bootstrap installs both). Enough to
// load the operator console, click, type, run a script and take a
// screenshot. Tests skip when the browser or its driver is absent.
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "core/process.h"
#include "tests/cluster/http_client.h"

namespace zenith::cluster::test {

/// Debian's paths of the browser and its driver.
inline const std::filesystem::path kChromium = "/usr/bin/chromium";
inline const std::filesystem::path kChromedriver = "/usr/bin/chromedriver";

/// Whether a headless browser test can run here.
inline bool browser_available() { return std::filesystem::exists(kChromium) && std::filesystem::exists(kChromedriver); }

/// Decodes standard base64 (WebDriver screenshots); stops at the first character outside the alphabet.
inline std::vector<std::uint8_t> decode_base64(const std::string& text) {
  std::vector<std::uint8_t> out;
  std::uint32_t bits = 0;
  int count = 0;
  for (const char c : text) {
    int v;
    if (c >= 'A' && c <= 'Z')
      v = c - 'A';
    else if (c >= 'a' && c <= 'z')
      v = c - 'a' + 26;
    else if (c >= '0' && c <= '9')
      v = c - '0' + 52;
    else if (c == '+')
      v = 62;
    else if (c == '/')
      v = 63;
    else
      break;
    bits = bits << 6 | static_cast<std::uint32_t>(v);
    count += 6;
    if (count >= 8) {
      count -= 8;
      out.push_back(static_cast<std::uint8_t>(bits >> count));
    }
  }
  return out;
}

/// One chromedriver process and one headless browser session. Every call
/// throws std::runtime_error with the driver's answer when it fails.
class WebDriver {
 public:
  /// Starts chromedriver (its log in `log`) on a port the driver picks itself
  /// and a headless session whose DevTools listen on `browser_port` (by
  /// default the browser picks a free port among the ephemeral ones, which the
  /// tests' own ports overlap). A port chosen here could be taken by another
  /// test between the choice and the driver's bind; port 0 cannot be.
  ///
  /// The driver and its browser get a temporary folder of their own (TMPDIR,
  /// through env, which executes the driver in its place): the browser leaves
  /// its singleton socket's folder there, not in /tmp, and the folder goes
  /// with this object.
  WebDriver(int browser_port, const std::filesystem::path& log)
      : temporary_(std::filesystem::temp_directory_path() /
                   ("zenith-webdriver-" + std::to_string(::getpid()) + "-" + std::to_string(browser_port))) {
    std::filesystem::remove_all(temporary_);
    std::filesystem::create_directories(temporary_);
    driver_ =
        core::spawn_process("/usr/bin/env", {"TMPDIR=" + temporary_.string(), kChromedriver.string(), "--port=0"}, log);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    const auto fail = [&](const std::string& why) {
      ::kill(driver_, SIGTERM);
      core::wait_for_exit(driver_, std::chrono::milliseconds(5000));
      remove_folder(temporary_);
      throw std::runtime_error("chromedriver " + why + "; its log (" + log.string() + "):\n" + read_text(log));
    };
    // "ChromeDriver was started successfully on port 38115."
    const std::string started = "started successfully on port ";
    for (;;) {
      const std::string text = read_text(log);
      if (const std::size_t at = text.find(started); at != std::string::npos) {
        port_ = std::atoi(text.c_str() + at + started.size());
        if (port_ > 0) break;
      }
      if (core::wait_for_exit(driver_, std::chrono::milliseconds(0))) fail("exited before it listened");
      if (std::chrono::steady_clock::now() > deadline) fail("did not say its port within 60 s");
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    while (http_request(port_, boost::beast::http::verb::get, "/status", "", "application/json", 5).status != 200) {
      if (std::chrono::steady_clock::now() > deadline) fail("did not answer /status on its port within 60 s");
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    const nlohmann::json capabilities = {
        {"capabilities",
         {{"alwaysMatch",
           {{"browserName", "chrome"},
            {"goog:chromeOptions",
             {{"binary", kChromium.string()},
              {"args",
               {"--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--window-size=1280,1500",
                "--remote-debugging-port=" + std::to_string(browser_port)}}}}}}}}};
    try {
      session_ = call(boost::beast::http::verb::post, "/session", capabilities)["sessionId"];
    } catch (const std::exception& e) {
      fail(std::string("started no browser session: ") + e.what());
    }
  }
  ~WebDriver() {
    if (!session_.empty())
      http_request(port_, boost::beast::http::verb::delete_, "/session/" + session_, "", "application/json", 30);
    ::kill(driver_, SIGTERM);
    core::wait_for_exit(driver_, std::chrono::milliseconds(5000));
    remove_folder(temporary_);
  }
  WebDriver(const WebDriver&) = delete;
  WebDriver& operator=(const WebDriver&) = delete;

  /// Removes `folder`, again while it comes back: a browser still quitting
  /// after its session ended can write its profile and singleton folders
  /// there after a first removal (one run in a few left them in /tmp). At
  /// most 5 s; it must stay gone for 300 ms.
  static void remove_folder(const std::filesystem::path& folder) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    std::error_code ignored;
    for (;;) {
      std::filesystem::remove_all(folder, ignored);
      std::this_thread::sleep_for(std::chrono::milliseconds(300));
      if (!std::filesystem::exists(folder, ignored) || std::chrono::steady_clock::now() > deadline) return;
    }
  }

  void open(const std::string& url) { call(boost::beast::http::verb::post, path("/url"), {{"url", url}}); }
  /// The element a CSS selector finds first.
  std::string element(const std::string& css) {
    const nlohmann::json found =
        call(boost::beast::http::verb::post, path("/element"), {{"using", "css selector"}, {"value", css}});
    return found.begin().value();  // {"element-6066-…": id}
  }
  void click(const std::string& element_id) {
    call(boost::beast::http::verb::post, path("/element/" + element_id + "/click"), nlohmann::json::object());
  }
  /// Types `text` into the element, as a user does (WebDriver key codes: "\ue004" is Tab).
  void type(const std::string& element_id, const std::string& text) {
    call(boost::beast::http::verb::post, path("/element/" + element_id + "/value"), {{"text", text}});
  }
  /// Runs `script` in the page; its return value.
  nlohmann::json script(const std::string& script) {
    return call(boost::beast::http::verb::post, path("/execute/sync"),
                {{"script", script}, {"args", nlohmann::json::array()}});
  }
  /// Saves a PNG of the window.
  void screenshot(const std::filesystem::path& file) {
    const std::vector<std::uint8_t> png =
        decode_base64(call(boost::beast::http::verb::get, path("/screenshot"), nullptr));
    std::ofstream(file, std::ios::binary)
        .write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  }

 private:
  static std::string read_text(const std::filesystem::path& file) {
    std::ifstream in(file);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  std::string path(const std::string& rest) const { return "/session/" + session_ + rest; }
  nlohmann::json call(boost::beast::http::verb verb, const std::string& target, const nlohmann::json& body) {
    const HttpReply r = http_request(port_, verb, target, body.is_null() ? "" : body.dump(), "application/json", 120);
    const nlohmann::json answer = r.json();
    if (r.status != 200 || !answer.is_object() || !answer.contains("value"))
      throw std::runtime_error("WebDriver " + target + ": HTTP " + std::to_string(r.status) + ": " +
                               r.body.substr(0, 2000));
    return answer["value"];
  }

  std::filesystem::path temporary_;  // the driver's and the browser's TMPDIR
  int port_ = 0;
  pid_t driver_ = -1;
  std::string session_;
};

}  // namespace zenith::cluster::test
