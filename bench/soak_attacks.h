#pragma once
// The attacks of the cluster soak (bench/cluster_soak.cpp --attacks;
// docs/cluster.md, "Soak"): what a web page, a clumsy operator or a
// stray process can do to a master on loopback, each checked for the answer
// a hardened master gives while the show goes on:
//
//   rebinding   a console command with Host "127.evil.example:P" and a
//               matching Origin (a page of a DNS name rebound to 127.0.0.1):
//               must be 403
//   slowloris   40 half-sent requests to the console, held 1–4 s; the
//               operator's own request meanwhile: must be 200
//   control     a no-cors text/plain POST carrying "quit" to the control
//               socket, or 256 KiB without a newline: must be closed (and
//               the show must not end early)
//   stray       `zenith node --name n0` while n0 is connected: must exit 2
//   preauth     50 connections sending a 1 MiB TableChunk header before any
//               handshake and 50 silent ones, held 1–3 s
//   osc         2 000 datagrams of random bytes and 100 messages whose
//               addresses carry newlines and escape codes
#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <random>
#include <string>
#include <vector>

namespace zenith::bench {

struct AttackPorts {
  int cluster = 0, console = 0, control = 0, osc = 0;
};

class SoakAttacks {
 public:
  using Clock = std::chrono::steady_clock;

  /// `node_args`: a node's arguments but its name and folders; `dir`: where strays log.
  SoakAttacks(std::filesystem::path zenith, std::vector<std::string> stray_args, std::filesystem::path dir,
              AttackPorts ports);
  ~SoakAttacks();
  SoakAttacks(const SoakAttacks&) = delete;
  SoakAttacks& operator=(const SoakAttacks&) = delete;

  /// One attack chosen at random; returns its name.
  std::string launch(std::mt19937& rng);
  /// Closes connections whose time is up, reaps strays that ended.
  void poll();
  /// Waits (at most 60 s) for strays still running, closes everything.
  void finish();

  /// "rebinding 12 (12 refused)" lines, and the failures.
  std::vector<std::string> report() const;
  std::vector<std::string> failures() const { return failures_; }
  int launched() const { return launched_; }

 private:
  struct Held {
    int fd;
    Clock::time_point close_at;
  };
  void rebinding();
  void slowloris(std::mt19937& rng);
  void control(std::mt19937& rng);
  void stray();
  void preauth(std::mt19937& rng);
  void osc(std::mt19937& rng);
  void hold(int fd, Clock::time_point until) { held_.push_back({fd, until}); }

  std::filesystem::path zenith_, dir_;
  std::vector<std::string> stray_args_;
  AttackPorts ports_;
  std::vector<Held> held_;
  std::vector<pid_t> strays_;
  std::map<std::string, int> counts_, passed_;
  std::vector<std::string> failures_;
  int launched_ = 0;
};

}  // namespace zenith::bench
