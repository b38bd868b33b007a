// A protocol message: an Envelope (frame 0) plus raw array frames (frames 1..k).
//
// Arrays are copied once into ZeroMQ frames and read in place on the other side: no per-element
// encoding. bench/bench_exchange compares this with packed repeated protobuf fields. A message
// given a SharedPayloadArena (a module serving ipc://) copies its large arrays into shared memory
// instead and sends empty frames (wire/shared_payload.hpp).
#pragma once

#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <zmq.hpp>

#include "rockcut/wire.pb.h"

namespace rockcut::wire {

/// A malformed or unexpected message (a programming or version error, not a user error).
class ProtocolError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class SharedPayloadArena;

/// One part of a multipart message, sent or received (blocking), resuming after a signal
/// handler ran (EINTR). Throws zmq::error_t on other errors.
void send_part(zmq::socket_t& socket, zmq::message_t& part, zmq::send_flags flags);
void receive_part(zmq::socket_t& socket, zmq::message_t& part);

class Message {
 public:
  Envelope envelope;

  /// Where add_array puts arrays of SharedPayloadArena::kMinBytes or more from now on (nullptr:
  /// in frames). Kept by clear(); the arena must outlive the message's sends.
  void use_arena(SharedPayloadArena* arena) { arena_ = arena; }

  /// Appends `values` (count * components doubles) as a raw frame named `name`.
  void add_array(std::string_view name, std::span<const double> values, std::uint32_t components);

  /// Moves every array of `other` into this message without copying the data (the coupler
  /// forwards kinematics and forces between modules this way).
  void take_arrays(Message& other);

  bool has_array(std::string_view name) const;
  /// The array `name`; throws ProtocolError if it is missing, has other components, or its
  /// header's count does not match the bytes that arrived.
  std::span<const double> array(std::string_view name, std::uint32_t components) const;
  /// The same, and throws ProtocolError unless it has exactly `count` rows (e.g. one per particle).
  std::span<const double> array(std::string_view name, std::uint32_t components,
                                std::size_t count) const;

  /// Drops the envelope and the arrays (keeps capacity for reuse).
  void clear();

  /// Sends all frames. Throws zmq::error_t on transport errors.
  void send(zmq::socket_t& socket);
  /// Receives one whole message (blocking). Throws ProtocolError if it is malformed; the whole
  /// message has been read from the socket then too.
  void receive(zmq::socket_t& socket);
  /// The same when frame 0 (`head`) was already received (a ROUTER socket's routing frames come
  /// before it).
  void receive_body(zmq::socket_t& socket, zmq::message_t& head);

  /// More array frames than this in one message are a protocol error (the protocol's largest,
  /// a State, carries a few tens).
  static constexpr std::size_t kMaxArrays = 256;

  /// Bytes of array payload, in frames or in shared memory (for transport statistics).
  std::size_t payload_bytes() const;
  /// The part of payload_bytes() that is in shared memory rather than in frames.
  std::size_t shared_payload_bytes() const;

 private:
  std::vector<zmq::message_t> frames_;  // frames_[i] holds envelope.arrays(i)
  // Small frames may be stored unaligned inside ZeroMQ; such arrays are copied here to read them.
  mutable std::vector<std::vector<double>> aligned_copies_;
  SharedPayloadArena* arena_ = nullptr;
};

}  // namespace rockcut::wire
