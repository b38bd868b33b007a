// The server side of bench_exchange: the force kernel both encodings run, the raw-frame server
// (the real wire::serve with a ModuleHandler) and the packed-field server, and the forked server
// processes with their async-signal-safe clean-up.
#pragma once

#include <sys/types.h>

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include <google/protobuf/repeated_field.h>
#include <zmq.hpp>

namespace rockcut::bench_exchange {

constexpr double kStiffness = 2.0;
constexpr double kDamping = 0.5;

enum class Transport { inproc, ipc, tcp };
enum class Encoding { raw, packed };
const char* name_of(Transport t);
const char* name_of(Encoding e);

/// f = -k x - c v over m values: every input is read and every output depends on it.
void force_kernel(const double* __restrict x, const double* __restrict v, double* __restrict f,
                  std::size_t m);
double process_cpu_s();
double position_value(std::size_t i);
double velocity_value(std::size_t i);
/// Checks a received force array against the kernel (a few samples; the values are exact).
void check_forces(std::span<const double> f, std::size_t values);
/// Appends `src` to a (cleared) repeated field: one reservation and one memcpy.
void fill(google::protobuf::RepeatedField<double>* field, std::span<const double> src);

/// Serves one session of the given encoding on `endpoint`; returns the exit code.
int run_server(zmq::context_t& context, Encoding encoding, const std::string& endpoint);

// Server processes and the ipc directory, reachable from signal handlers without allocating.
extern char g_ipc_dir[64];
extern char g_ipc_files[2][128];
/// Forks a server process that creates its own context and dies with this one.
pid_t fork_server(Encoding encoding, const std::string& endpoint);
pid_t* child_slot(pid_t pid);
void kill_children();   // async-signal-safe
void remove_ipc_dir();  // async-signal-safe
void on_signal(int sig);
void at_exit();
/// `count` distinct loopback ports that were free a moment ago.
std::vector<int> free_tcp_ports(int count);

}  // namespace rockcut::bench_exchange
