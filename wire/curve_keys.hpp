// CURVE keys for sessions over tcp (ZeroMQ's own authentication and encryption, RFC 26/CurveZMQ).
//
// A key directory holds one key pair per party: NAME.public and NAME.secret, each one line of
// Z85 text (40 characters) as zmq_curve_keypair makes them; NAME is "coupler", "dem_module" or
// "fluid_module". The secret files are readable by their owner only, and a secret file others
// can read is refused (like ssh's private keys). A module serving with keys accepts only the
// coupler's public key; the coupler checks the module's public key in the handshake.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace rockcut::wire {

struct CurveKeyPair {
  std::string public_key;  ///< Z85, 40 characters
  std::string secret_key;  ///< Z85, 40 characters
};

/// Creates `dir` (mode 0700) if needed and a new key pair NAME.public (0644) and NAME.secret
/// (0600) for each of `names`. Refuses (std::runtime_error) to overwrite an existing key file.
void make_curve_keys(const std::filesystem::path& dir, const std::vector<std::string>& names);

/// Reads NAME.public from `dir`. Throws std::runtime_error naming the file if it is missing or
/// not a Z85 key.
std::string read_public_key(const std::filesystem::path& dir, const std::string& name);

/// Reads NAME.public and NAME.secret from `dir`; also refuses a secret file that its group or
/// others may read.
CurveKeyPair read_key_pair(const std::filesystem::path& dir, const std::string& name);

}  // namespace rockcut::wire
