#include "wire/curve_keys.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include <zmq.h>

namespace rockcut::wire {

namespace fs = std::filesystem;

namespace {

constexpr std::size_t kZ85KeyChars = 40;

void write_new(const fs::path& path, const std::string& text, mode_t mode) {
  const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, mode);
  if (fd < 0) {
    throw std::runtime_error(path.string() + ": cannot create the key file: " +
                             std::strerror(errno) +
                             (errno == EEXIST ? " (remove the old keys first)" : ""));
  }
  const std::string line = text + "\n";
  const bool ok = write(fd, line.data(), line.size()) == static_cast<ssize_t>(line.size()) &&
                  fchmod(fd, mode) == 0;
  close(fd);
  if (!ok) throw std::runtime_error(path.string() + ": cannot write the key file");
}

std::string read_key(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path.string() + ": cannot read the key file");
  char buffer[kZ85KeyChars + 2] = {};
  in.read(buffer, sizeof buffer);
  std::string key(buffer, static_cast<std::size_t>(in.gcount()));
  while (!key.empty() && (key.back() == '\n' || key.back() == '\r')) key.pop_back();
  std::uint8_t binary[32];
  if (key.size() != kZ85KeyChars || zmq_z85_decode(binary, key.c_str()) == nullptr) {
    throw std::runtime_error(path.string() + ": not a CURVE key (one line of 40 Z85 characters, "
                             "as `coupler keygen` writes)");
  }
  return key;
}

}  // namespace

void make_curve_keys(const fs::path& dir, const std::vector<std::string>& names) {
  if (!zmq_has("curve")) {
    throw std::runtime_error("this libzmq has no CURVE security (built without libsodium)");
  }
  std::error_code ec;
  if (!fs::exists(dir) && (!fs::create_directories(dir, ec) || ec)) {
    throw std::runtime_error(dir.string() + ": cannot create the key directory: " + ec.message());
  }
  ::chmod(dir.c_str(), 0700);
  for (const std::string& name : names) {
    char public_key[kZ85KeyChars + 1];
    char secret_key[kZ85KeyChars + 1];
    if (zmq_curve_keypair(public_key, secret_key) != 0) {
      throw std::runtime_error(std::string("zmq_curve_keypair failed: ") + zmq_strerror(errno));
    }
    write_new(dir / (name + ".secret"), secret_key, 0600);
    write_new(dir / (name + ".public"), public_key, 0644);
  }
}

std::string read_public_key(const fs::path& dir, const std::string& name) {
  return read_key(dir / (name + ".public"));
}

CurveKeyPair read_key_pair(const fs::path& dir, const std::string& name) {
  const fs::path secret = dir / (name + ".secret");
  struct stat st {};
  if (stat(secret.c_str(), &st) != 0) {
    throw std::runtime_error(secret.string() + ": cannot read the key file: " +
                             std::strerror(errno));
  }
  if ((st.st_mode & 077) != 0) {
    throw std::runtime_error(secret.string() + ": the secret key may be read by others (chmod 600 "
                             "it, or make new keys)");
  }
  return {read_public_key(dir, name), read_key(secret)};
}

}  // namespace rockcut::wire
