#include "wire/state_message.hpp"

namespace rockcut::wire {

void put_state(const state::StateArchive& archive, State& body, Message& message) {
  for (const auto& [name, text] : archive.texts()) (*body.mutable_texts())[name] = text;
  for (const state::StateArray& a : archive.arrays()) {
    message.add_array(a.name, a.values, a.components);
  }
}

state::StateArchive take_state(const State& body, const Message& message) {
  state::StateArchive archive;
  for (const auto& [name, text] : body.texts()) archive.put_text(name, text);
  for (const ArrayHeader& h : message.envelope.arrays()) {
    archive.put(h.name(), message.array(h.name(), h.components()), h.components());
  }
  return archive;
}

}  // namespace rockcut::wire
