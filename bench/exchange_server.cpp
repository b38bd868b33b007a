#include "exchange_server.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <stdexcept>

#include "bench_packed.pb.h"
#include "wire/message.hpp"
#include "wire/module_server.hpp"
#include "wire/protocol.hpp"

namespace rockcut::bench_exchange {

namespace wire = rockcut::wire;
using rockcut::bench::PackedForces;
using rockcut::bench::PackedKinematics;

// ---------------------------------------------------------------------------------------------
// The server's work: a cheap force from the kinematics, so every input value is read and every
// output value depends on it (nothing can be optimised away).

void force_kernel(const double* __restrict x, const double* __restrict v, double* __restrict f,
                  std::size_t m) {
  for (std::size_t i = 0; i < m; ++i) f[i] = -kStiffness * x[i] - kDamping * v[i];
}

double process_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double position_value(std::size_t i) { return 1e-3 * static_cast<double>(i); }
double velocity_value(std::size_t i) { return 0.25 - 1e-4 * static_cast<double>(i % 977); }

/// Checks a received force array against the kernel (a few samples; the values are exact).
void check_forces(std::span<const double> f, std::size_t values) {
  if (f.size() != values) {
    throw std::runtime_error("reply has " + std::to_string(f.size()) + " force values, expected " +
                             std::to_string(values));
  }
  for (std::size_t i : {std::size_t{0}, values / 2, values - 1}) {
    const double expected = -kStiffness * position_value(i) - kDamping * velocity_value(i);
    if (f[i] != expected) throw std::runtime_error("wrong force value at " + std::to_string(i));
  }
}

/// Appends `src` to a (cleared) repeated field: one reservation and one memcpy.
void fill(google::protobuf::RepeatedField<double>* field, std::span<const double> src) {
  const int count = static_cast<int>(src.size());
  field->Reserve(field->size() + count);
  std::memcpy(field->AddNAlreadyReserved(count), src.data(), src.size_bytes());
}

// ---------------------------------------------------------------------------------------------
// Servers

class ForceHandler : public wire::ModuleHandler {
 public:
  wire::ModuleKind kind() const override { return wire::MODULE_KIND_FLUID; }
  std::string name() const override { return "bench_exchange server"; }
  std::string version() const override { return ROCKCUT_VERSION; }
  std::vector<std::string> models() const override { return {"bench_force"}; }

  void handle(const wire::Message& request, wire::Message& reply) override {
    if (!request.envelope.has_fluid_step()) throw wire::ProtocolError("expected FluidStep");
    const std::span<const double> x = request.array(wire::field::kPosition, 2);
    const std::span<const double> v = request.array(wire::field::kVelocityHalf, 2);
    if (x.size() != v.size()) throw wire::ProtocolError("position and velocity_half differ");
    force_.resize(x.size());
    force_kernel(x.data(), v.data(), force_.data(), x.size());
    reply.add_array(wire::field::kForce, force_, 2);
    (*reply.envelope.mutable_fluid_result()->mutable_scalars())["server_cpu_s"] = process_cpu_s();
  }

 private:
  std::vector<double> force_;  // the module's own force array, sent from here
};

/// The packed-encoding server: a REP loop like wire::serve(). An empty request means "stop" (it is
/// answered with an empty reply); a malformed one is answered with an empty reply.
int serve_packed(zmq::context_t& context, const std::string& endpoint) {
  zmq::socket_t socket(context, zmq::socket_type::rep);
  socket.set(zmq::sockopt::linger, 0);
  socket.bind(endpoint);
  PackedKinematics request;
  PackedForces reply;
  std::vector<double> force;
  for (;;) {
    zmq::message_t in;
    if (!socket.recv(in, zmq::recv_flags::none)) return 1;
    if (in.size() == 0) {
      socket.send(zmq::message_t(), zmq::send_flags::none);
      return 0;
    }
    if (!request.ParseFromArray(in.data(), static_cast<int>(in.size())) ||
        request.position_size() != request.velocity_half_size()) {
      socket.send(zmq::message_t(), zmq::send_flags::none);
      continue;
    }
    const std::size_t m = static_cast<std::size_t>(request.position_size());
    force.resize(m);
    force_kernel(request.position().data(), request.velocity_half().data(), force.data(), m);
    reply.Clear();
    fill(reply.mutable_force(), force);
    reply.set_server_cpu_s(process_cpu_s());
    zmq::message_t out(reply.ByteSizeLong());
    reply.SerializeToArray(out.data(), static_cast<int>(out.size()));
    socket.send(out, zmq::send_flags::none);
  }
}


const char* name_of(Transport t) {
  switch (t) {
    case Transport::inproc: return "inproc";
    case Transport::ipc: return "ipc";
    case Transport::tcp: return "tcp";
  }
  return "?";
}
const char* name_of(Encoding e) { return e == Encoding::raw ? "raw" : "packed"; }

int run_server(zmq::context_t& context, Encoding encoding, const std::string& endpoint) {
  if (encoding == Encoding::raw) {
    ForceHandler handler;
    return wire::serve(context, endpoint, handler);
  }
  return serve_packed(context, endpoint);
}

// Child processes, kept where the signal handler and atexit can reach them without allocating.
constexpr int kMaxChildren = 8;
namespace {
pid_t g_children[kMaxChildren] = {};
int g_child_count = 0;
}  // namespace
char g_ipc_dir[64] = {};
char g_ipc_files[2][128] = {};

void kill_children() {  // async-signal-safe
  for (int i = 0; i < g_child_count; ++i) {
    const pid_t pid = g_children[i];
    if (pid <= 0) continue;
    kill(pid, SIGKILL);
    while (waitpid(pid, nullptr, 0) < 0 && errno == EINTR) {
    }
    g_children[i] = 0;
  }
}

void remove_ipc_dir() {  // async-signal-safe
  if (g_ipc_dir[0] == '\0') return;
  for (const char* f : g_ipc_files) {
    if (f[0] != '\0') unlink(f);
  }
  rmdir(g_ipc_dir);
  g_ipc_dir[0] = '\0';
}

void on_signal(int sig) {
  kill_children();
  remove_ipc_dir();
  _exit(128 + sig);
}

void at_exit() {
  kill_children();
  remove_ipc_dir();
}

pid_t* child_slot(pid_t pid) {
  for (int i = 0; i < g_child_count; ++i) {
    if (g_children[i] == pid) return &g_children[i];
  }
  return nullptr;
}

/// Forks a server process. The child creates its own ZeroMQ context after the fork (the parent
/// has none yet) and dies with the parent.
pid_t fork_server(Encoding encoding, const std::string& endpoint) {
  if (g_child_count == kMaxChildren) throw std::runtime_error("too many server processes");
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  if (pid == 0) {
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(3);
    int code = 2;
    try {
      zmq::context_t context(1);
      code = run_server(context, encoding, endpoint);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "bench_exchange server %s: %s\n", endpoint.c_str(), e.what());
    }
    _exit(code);  // no atexit handlers, no stdio flush of the parent's buffers
  }
  g_children[g_child_count++] = pid;
  return pid;
}

/// Two free loopback ports (both probed before either is released, so they differ).
std::vector<int> free_tcp_ports(int count) {
  std::vector<int> fds, ports;
  for (int i = 0; i < count; ++i) {
    const int fd = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    addr.sin_port = 0;
    socklen_t len = sizeof addr;
    if (fd < 0 || bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 ||
        getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) != 0) {
      throw std::runtime_error(std::string("cannot find a free tcp port: ") + std::strerror(errno));
    }
    fds.push_back(fd);
    ports.push_back(ntohs(addr.sin_port));
  }
  for (int fd : fds) close(fd);
  return ports;
}

}  // namespace rockcut::bench_exchange
