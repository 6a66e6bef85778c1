// Writes the seed corpus of frame_decoder_fuzzer into a directory: every
// sample message and every maximum-size message (except the 1 MiB TableChunk)
// as its own file, and all samples in a row, each file starting with the
// fuzzer's control byte (docs/protocol.md, "Fuzzing").
// Usage: frame_decoder_corpus DIR
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "cluster/protocol/messages.h"
#include "tests/cluster/sample_messages.h"

int main(int argc, char** argv) {
  using namespace zenith::cluster;
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s DIR\n", argv[0]);
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  std::filesystem::create_directories(dir);
  int written = 0;
  const auto write = [&](const std::string& name, std::uint8_t control, const std::vector<std::uint8_t>& bytes) {
    std::ofstream out(dir / name, std::ios::binary);
    out.put(static_cast<char>(control));
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (!out) {
      std::fprintf(stderr, "cannot write %s\n", (dir / name).c_str());
      std::exit(1);
    }
    ++written;
  };
  std::vector<std::uint8_t> all;
  for (const Message& m : sample_messages()) {
    const auto frame = encode(m);
    const std::string type = to_string(message_type(m));
    write("sample_" + type, 0x01, frame);
    write("sample_" + type + "_split", 0x06, frame);
    all.insert(all.end(), frame.begin(), frame.end());
  }
  write("all_samples", 0x01, all);
  for (const Message& m : max_size_messages()) {
    if (message_type(m) == MessageType::table_chunk) continue;
    write(std::string("max_") + to_string(message_type(m)), 0x01, encode(m));
  }
  std::printf("wrote %d seed inputs to %s\n", written, dir.c_str());
  return 0;
}
