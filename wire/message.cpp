#include "wire/message.hpp"

#include <cerrno>
#include <cstdint>
#include <cstring>

#include "wire/protocol.hpp"
#include "wire/shared_payload.hpp"

namespace rockcut::wire {

std::string_view kind_name(ModuleKind kind) {
  switch (kind) {
    case MODULE_KIND_DEM: return "dem_module";
    case MODULE_KIND_FLUID: return "fluid_module";
    default: return "unknown module";
  }
}

void Message::add_array(std::string_view name, std::span<const double> values,
                        std::uint32_t components) {
  if (components == 0 || values.size() % components != 0) {
    throw ProtocolError("array '" + std::string(name) + "': " + std::to_string(values.size()) +
                        " values are not a multiple of " + std::to_string(components));
  }
  ArrayHeader* header = envelope.add_arrays();
  header->set_name(std::string(name));
  header->set_dtype(DTYPE_F64);
  header->set_count(values.size() / components);
  header->set_components(components);
  if (arena_ && values.size_bytes() >= SharedPayloadArena::kMinBytes) {
    arena_->write(values, *header);
    frames_.emplace_back();  // empty: the values are in the arena's segment
    return;
  }
  frames_.emplace_back(values.data(), values.size_bytes());
}

void Message::take_arrays(Message& other) {
  for (int i = 0; i < other.envelope.arrays_size(); ++i) {
    *envelope.add_arrays() = other.envelope.arrays(i);
    frames_.push_back(std::move(other.frames_[static_cast<std::size_t>(i)]));
  }
  other.envelope.clear_arrays();
  other.frames_.clear();
  other.aligned_copies_.clear();
}

bool Message::has_array(std::string_view name) const {
  for (const ArrayHeader& h : envelope.arrays()) {
    if (h.name() == name) return true;
  }
  return false;
}

std::span<const double> Message::array(std::string_view name, std::uint32_t components) const {
  for (int i = 0; i < envelope.arrays_size(); ++i) {
    const ArrayHeader& h = envelope.arrays(i);
    if (h.name() != name) continue;
    if (components == 0 || h.components() != components || h.dtype() != DTYPE_F64) {
      throw ProtocolError("array '" + std::string(name) + "' has " +
                          std::to_string(h.components()) + " components, expected " +
                          std::to_string(components));
    }
    if (!h.shared_segment().empty()) return read_shared(h);
    const zmq::message_t& frame = frames_.at(static_cast<std::size_t>(i));
    // Compared by division: count * components * 8 may wrap for a count a peer made up.
    const std::size_t doubles = frame.size() / sizeof(double);
    if (frame.size() % sizeof(double) != 0 || h.count() != doubles / components ||
        doubles % components != 0) {
      throw ProtocolError("array '" + std::string(name) + "': frame of " +
                          std::to_string(frame.size()) + " bytes for " +
                          std::to_string(h.count()) + " x " + std::to_string(components) +
                          " doubles");
    }
    const std::size_t n = doubles;
    if (n == 0) return {};  // an empty frame's data() may be null or unaligned: nothing to copy
    const void* data = frame.data();
    if (reinterpret_cast<std::uintptr_t>(data) % alignof(double) == 0) {
      return {static_cast<const double*>(data), n};
    }
    auto& copy = aligned_copies_.emplace_back(n);
    std::memcpy(copy.data(), data, frame.size());
    return copy;
  }
  throw ProtocolError("message lacks the array '" + std::string(name) + "'");
}

std::span<const double> Message::array(std::string_view name, std::uint32_t components,
                                       std::size_t count) const {
  const std::span<const double> values = array(name, components);
  if (values.size() != count * components) {
    throw ProtocolError("array '" + std::string(name) + "' has " +
                        std::to_string(values.size() / components) + " rows, expected " +
                        std::to_string(count));
  }
  return values;
}

void Message::clear() {
  envelope.Clear();
  frames_.clear();
  aligned_copies_.clear();
}

std::size_t Message::payload_bytes() const {
  std::size_t bytes = 0;
  for (std::size_t i = 0; i < frames_.size(); ++i) {
    const ArrayHeader& h = envelope.arrays(static_cast<int>(i));
    bytes += h.shared_segment().empty() ? frames_[i].size()
                                        : h.count() * h.components() * sizeof(double);
  }
  return bytes;
}

std::size_t Message::shared_payload_bytes() const {
  std::size_t bytes = 0;
  for (const ArrayHeader& h : envelope.arrays()) {
    if (!h.shared_segment().empty()) bytes += h.count() * h.components() * sizeof(double);
  }
  return bytes;
}

void send_part(zmq::socket_t& socket, zmq::message_t& part, zmq::send_flags flags) {
  for (;;) {
    try {
      socket.send(part, flags);
      return;
    } catch (const zmq::error_t& e) {
      if (e.num() != EINTR) throw;
    }
  }
}

void Message::send(zmq::socket_t& socket) {
  const std::string head_bytes = envelope.SerializeAsString();
  zmq::message_t head(head_bytes.data(), head_bytes.size());
  const bool more = !frames_.empty();
  send_part(socket, head, more ? zmq::send_flags::sndmore : zmq::send_flags::none);
  for (std::size_t i = 0; i < frames_.size(); ++i) {
    const bool last = i + 1 == frames_.size();
    send_part(socket, frames_[i], last ? zmq::send_flags::none : zmq::send_flags::sndmore);
  }
  frames_.clear();  // sent frames are moved out by ZeroMQ
}

void receive_part(zmq::socket_t& socket, zmq::message_t& part) {
  for (;;) {
    try {
      if (socket.recv(part, zmq::recv_flags::none)) return;
    } catch (const zmq::error_t& e) {
      if (e.num() != EINTR) throw;
    }
  }
}

void Message::receive(zmq::socket_t& socket) {
  clear();
  zmq::message_t head;
  receive_part(socket, head);
  receive_body(socket, head);
}

void Message::receive_body(zmq::socket_t& socket, zmq::message_t& head) {
  clear();
  // The whole multipart message is read before anything is checked, so a malformed one leaves
  // no parts behind to be taken for the next message.
  bool more = head.more();
  bool too_many = false;
  while (more) {
    zmq::message_t part;
    receive_part(socket, part);
    more = part.more();
    if (frames_.size() < kMaxArrays) {
      frames_.push_back(std::move(part));
    } else {
      too_many = true;
    }
  }
  if (too_many) {
    const std::size_t n = frames_.size();
    clear();
    throw ProtocolError("more than " + std::to_string(n) + " array frames in one message");
  }
  if (head.size() > static_cast<std::size_t>(INT32_MAX) ||
      !envelope.ParseFromArray(head.data(), static_cast<int>(head.size()))) {
    clear();
    throw ProtocolError("frame 0 is not a rockcut.wire.Envelope");
  }
  if (frames_.size() != static_cast<std::size_t>(envelope.arrays_size())) {
    const std::string what = "envelope announces " + std::to_string(envelope.arrays_size()) +
                             " arrays, " + std::to_string(frames_.size()) + " frames arrived";
    clear();
    throw ProtocolError(what);
  }
}

}  // namespace rockcut::wire
