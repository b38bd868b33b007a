// A module's state (wire/state_archive.hpp) on the wire: its arrays as the message's array
// frames (through shared memory over ipc://, like any large array), its texts in the State body.
#pragma once

#include "rockcut/wire.pb.h"
#include "wire/state_archive.hpp"
#include "wire/message.hpp"

namespace rockcut::wire {

/// Fills `body` with the texts of `archive` and appends its arrays to `message`.
void put_state(const state::StateArchive& archive, State& body, Message& message);

/// The state carried by `message` (its arrays) and `body` (its texts).
state::StateArchive take_state(const State& body, const Message& message);

}  // namespace rockcut::wire
