// bench_exchange: the cost of ONE coupling exchange as the coupler does it with the fluid module.
//
// The client (coupler side) sends kinematics -- "position" and "velocity_half", 2 * n doubles each --
// and receives forces -- "force", 2 * n doubles -- for n particles, over
//   inproc  server thread in the same ZeroMQ context,
//   ipc     server process (forked before any context exists), socket in a private temp dir,
//   tcp     server process on 127.0.0.1 and a free port,
// in two encodings:
//   raw     the project's wire::Message: Envelope in frame 0, one raw frame per array (add_array
//           copies each array once; the receiver reads the frame in place). The client is
//           wire::ModuleClient and the server wire::serve() with a ModuleHandler: the real code.
//           Over ipc, arrays of 64 KiB or more go through shared memory instead (both sides;
//           ROCKCUT_WIRE_SHARED_MEMORY=0 keeps them in frames).
//   packed  bench_packed.proto: the same data as packed `repeated double` fields in frame 0 only
//           (fill the repeated fields, SerializeToArray into a zmq::message_t, ParseFromArray).
//           Client and server loops are written here and wait the same way ModuleClient does.
// Baselines: "memcpy" copies the same bytes once (what a perfect transport would cost) and "kernel"
// is the server's force function alone (it is part of every exchange).
//
// Counters: particles = n; GB/s = (kinematics + force bytes = 48 n) / real time per exchange;
// cpu_us = CPU time per exchange of both sides, all threads (ZeroMQ I/O threads included): the
// client process's clock plus the server process's, which every reply carries.
// Servers are started once in main() and stopped (Shutdown, then SIGKILL + waitpid if needed) before
// exit, also on SIGINT/SIGTERM/SIGHUP; server processes also die with this one (PR_SET_PDEATHSIG).
#include <arpa/inet.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include <benchmark/benchmark.h>
#include <zmq.hpp>

#include "bench_packed.pb.h"
#include "exchange_server.hpp"
#include "wire/message.hpp"
#include "wire/module_client.hpp"
#include "wire/module_server.hpp"
#include "wire/protocol.hpp"
#include "wire/shared_payload.hpp"

namespace {

using namespace std::chrono_literals;
namespace wire = rockcut::wire;
using rockcut::bench::PackedForces;
using rockcut::bench::PackedKinematics;
using namespace rockcut::bench_exchange;

constexpr std::int64_t kSizes[] = {1'000, 10'000, 100'000, 1'000'000};
// Defaults added to the command line unless it sets them (so they can be overridden): 0.2 s per
// repetition, 5 repetitions shuffled among all benchmarks (a burst of load on a shared machine then
// hits one repetition of several benchmarks, not all of one), the console showing only
// mean/median/stddev/cv/min. About a minute in all on 2 cores.
constexpr const char* kDefaultFlags[] = {
    "--benchmark_min_time=0.2", "--benchmark_repetitions=5",
    "--benchmark_enable_random_interleaving=true", "--benchmark_display_aggregates_only=true"};
constexpr auto kExchangeTimeout = 60s;
constexpr auto kStartTimeout = 10s;
constexpr auto kStopTimeout = 2s;


// ---------------------------------------------------------------------------------------------
// One server and the client connected to it.

struct Link {
  Transport transport;
  Encoding encoding;
  std::string endpoint;
  pid_t pid = 0;       // server process (ipc, tcp)
  std::thread thread;  // server thread (inproc)
  std::string failure;  // why the server is gone, once known

  std::unique_ptr<wire::ModuleClient> raw;  // Encoding::raw
  wire::Message request, reply;
  // ipc: the kinematics go through shared memory as the DEM's do in a run (the coupler forwards
  // the DEM's headers); ROCKCUT_WIRE_SHARED_MEMORY=0 keeps them in frames, on both sides.
  std::unique_ptr<wire::SharedPayloadArena> arena;
  std::unique_ptr<zmq::socket_t> socket;    // Encoding::packed
  PackedKinematics packed_request;
  PackedForces packed_reply;

  std::string label() const {
    return std::string(name_of(transport)) + "/" + name_of(encoding) + " server at " + endpoint;
  }

  /// Why the server is gone, or nothing while it runs.
  std::optional<std::string> dead() {
    if (!failure.empty()) return failure;
    if (pid > 0) {
      int status = 0;
      if (waitpid(pid, &status, WNOHANG) == pid) {
        if (pid_t* slot = child_slot(pid)) *slot = 0;
        pid = 0;
        failure = WIFSIGNALED(status) ? "killed by signal " + std::to_string(WTERMSIG(status))
                                      : "exited with " + std::to_string(WEXITSTATUS(status));
        return failure;
      }
    }
    return std::nullopt;
  }

  void connect(zmq::context_t& context) {
    if (encoding == Encoding::raw) {
      wire::ClientHooks hooks;
      hooks.dead = [this] { return dead(); };
      raw = std::make_unique<wire::ModuleClient>(context, label(), endpoint, kStartTimeout, hooks);
      arena = wire::SharedPayloadArena::for_endpoint(endpoint);
      request.use_arena(arena.get());
      wire::Message hello, answer;
      hello.envelope.mutable_hello()->set_protocol_version(wire::kProtocolVersion);
      hello.envelope.mutable_hello()->set_expected_kind(wire::MODULE_KIND_FLUID);
      raw->request(hello, answer);
      if (!answer.envelope.has_hello_reply()) throw std::runtime_error(label() + ": no HelloReply");
      raw->set_timeout(kExchangeTimeout);
    } else {
      socket = std::make_unique<zmq::socket_t>(context, zmq::socket_type::req);
      socket->set(zmq::sockopt::linger, 0);
      socket->connect(endpoint);
      const std::vector<double> one = {position_value(0), position_value(1)};
      const std::vector<double> one_v = {velocity_value(0), velocity_value(1)};
      check_forces(exchange_packed(one, one_v, kStartTimeout), 2);
    }
  }

  /// Waits for the reply like wire::ModuleClient::receive: poll in 50 ms slices, watch the server.
  void wait_readable(std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    for (;;) {
      zmq::pollitem_t item{socket->handle(), 0, ZMQ_POLLIN, 0};
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
          deadline - std::chrono::steady_clock::now());
      zmq::poll(&item, 1, std::clamp(left, 0ms, 50ms));
      if (item.revents & ZMQ_POLLIN) return;
      if (auto why = dead()) throw std::runtime_error(label() + ": the process " + *why);
      if (std::chrono::steady_clock::now() >= deadline) {
        throw std::runtime_error(label() + ": no reply within the timeout");
      }
    }
  }

  /// One exchange in the raw encoding, exactly as the coupler does it; returns the forces in place.
  std::span<const double> exchange_raw(std::span<const double> x, std::span<const double> v) {
    request.clear();
    wire::FluidStep* step = request.envelope.mutable_fluid_step();
    step->set_dt_s(1e-6);
    step->set_time_s(1.0);
    request.add_array(wire::field::kPosition, x, 2);
    request.add_array(wire::field::kVelocityHalf, v, 2);
    raw->request(request, reply);
    if (!reply.envelope.has_fluid_result()) throw std::runtime_error(label() + ": no FluidResult");
    return reply.array(wire::field::kForce, 2);
  }

  /// One exchange in the packed encoding; returns the forces (in the parsed message).
  std::span<const double> exchange_packed(std::span<const double> x, std::span<const double> v,
                                          std::chrono::milliseconds timeout = kExchangeTimeout) {
    packed_request.Clear();
    packed_request.set_dt_s(1e-6);
    packed_request.set_time_s(1.0);
    fill(packed_request.mutable_position(), x);
    fill(packed_request.mutable_velocity_half(), v);
    zmq::message_t out(packed_request.ByteSizeLong());
    packed_request.SerializeToArray(out.data(), static_cast<int>(out.size()));
    socket->send(out, zmq::send_flags::none);
    wait_readable(timeout);
    zmq::message_t in;
    if (!socket->recv(in, zmq::recv_flags::none)) throw std::runtime_error("receive interrupted");
    if (in.size() == 0 || !packed_reply.ParseFromArray(in.data(), static_cast<int>(in.size()))) {
      throw std::runtime_error(label() + ": malformed reply");
    }
    return {packed_reply.force().data(), static_cast<std::size_t>(packed_reply.force_size())};
  }

  /// The server process's CPU clock as stamped in the last reply [s].
  double server_cpu_s() const {
    if (encoding == Encoding::packed) return packed_reply.server_cpu_s();
    const auto& scalars = reply.envelope.fluid_result().scalars();
    const auto it = scalars.find("server_cpu_s");
    return it == scalars.end() ? 0.0 : it->second;
  }

  std::span<const double> exchange(std::span<const double> x, std::span<const double> v) {
    return encoding == Encoding::raw ? exchange_raw(x, v) : exchange_packed(x, v);
  }

  /// Asks the server to stop; closes the client. Never throws.
  void stop() {
    try {
      if (raw) {
        wire::Message bye, answer;
        bye.envelope.mutable_shutdown();
        raw->set_timeout(std::chrono::duration_cast<std::chrono::milliseconds>(kStopTimeout));
        raw->request(bye, answer);
      } else if (socket) {
        socket->send(zmq::message_t(), zmq::send_flags::none);
        wait_readable(std::chrono::duration_cast<std::chrono::milliseconds>(kStopTimeout));
        zmq::message_t in;
        (void)socket->recv(in, zmq::recv_flags::none);
      }
    } catch (const std::exception&) {
      // The server may already be gone, or its answer lost (linger 0): it is killed below.
    }
    raw.reset();
    socket.reset();
  }

  /// Reaps the server process (waits up to kStopTimeout, then SIGKILL).
  void reap() {
    if (pid <= 0) return;
    const auto deadline = std::chrono::steady_clock::now() + kStopTimeout;
    int status = 0;
    pid_t r = 0;
    while ((r = waitpid(pid, &status, WNOHANG)) == 0 && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(10ms);
    }
    if (r == 0) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
    }
    if (pid_t* slot = child_slot(pid)) *slot = 0;
    pid = 0;
  }
};

std::vector<std::unique_ptr<Link>> g_links;

Link* find_link(Transport t, Encoding e) {
  for (auto& l : g_links) {
    if (l->transport == t && l->encoding == e) return l.get();
  }
  return nullptr;
}

// ---------------------------------------------------------------------------------------------
// Benchmarks

struct Kinematics {
  std::vector<double> x, v;
  explicit Kinematics(std::size_t n) : x(2 * n), v(2 * n) {
    for (std::size_t i = 0; i < 2 * n; ++i) {
      x[i] = position_value(i);
      v[i] = velocity_value(i);
    }
  }
};

void set_counters(benchmark::State& state, std::size_t n) {
  const double bytes = 3.0 * 2.0 * static_cast<double>(n) * sizeof(double);  // 2 out, 1 back
  state.counters["particles"] = static_cast<double>(n);
  state.counters["GB/s"] =
      benchmark::Counter(bytes / 1e9, benchmark::Counter::kIsIterationInvariantRate);
}

void BM_Exchange(benchmark::State& state, Transport transport, Encoding encoding) {
  const std::size_t n = static_cast<std::size_t>(state.range(0));
  Link* link = find_link(transport, encoding);
  if (link == nullptr || !(link->raw || link->socket)) {
    state.SkipWithError("server not running");
    return;
  }
  const Kinematics k(n);
  try {
    check_forces(link->exchange(k.x, k.v), 2 * n);  // warm-up, and proof the data arrives
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  const double client_cpu0 = process_cpu_s();
  const double server_cpu0 = link->server_cpu_s();
  std::span<const double> f;
  for (auto _ : state) {
    try {
      f = link->exchange(k.x, k.v);
    } catch (const std::exception& e) {
      state.SkipWithError(e.what());
      break;
    }
    benchmark::DoNotOptimize(f.data());
  }
  double cpu_s = process_cpu_s() - client_cpu0;
  // An inproc server is a thread of this process: its time is in the client's clock already.
  if (transport != Transport::inproc) cpu_s += link->server_cpu_s() - server_cpu0;
  state.counters["cpu_us"] = benchmark::Counter(1e6 * cpu_s, benchmark::Counter::kAvgIterations);
  try {
    if (!f.empty()) check_forces(f, 2 * n);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
  }
  set_counters(state, n);
}

/// What a perfect transport would cost: the same bytes copied once, into buffers already mapped.
void BM_Memcpy(benchmark::State& state) {
  const std::size_t n = static_cast<std::size_t>(state.range(0));
  const Kinematics k(n);
  std::vector<double> force(2 * n, 1.0);
  std::vector<double> x_dst(2 * n, 0.0), v_dst(2 * n, 0.0), f_dst(2 * n, 0.0);
  for (auto _ : state) {
    std::memcpy(x_dst.data(), k.x.data(), 2 * n * sizeof(double));
    std::memcpy(v_dst.data(), k.v.data(), 2 * n * sizeof(double));
    std::memcpy(f_dst.data(), force.data(), 2 * n * sizeof(double));
    benchmark::ClobberMemory();
  }
  benchmark::DoNotOptimize(x_dst.data());
  benchmark::DoNotOptimize(v_dst.data());
  benchmark::DoNotOptimize(f_dst.data());
  set_counters(state, n);
}

/// The server's force function alone (one pass: read 2 arrays, write 1); every exchange runs it.
void BM_Kernel(benchmark::State& state) {
  const std::size_t n = static_cast<std::size_t>(state.range(0));
  const Kinematics k(n);
  std::vector<double> force(2 * n, 0.0);
  for (auto _ : state) {
    force_kernel(k.x.data(), k.v.data(), force.data(), 2 * n);
    benchmark::ClobberMemory();
  }
  check_forces(force, 2 * n);
  set_counters(state, n);
}

template <typename B>
void configure(B* b) {
  for (std::int64_t n : kSizes) b->Arg(n);
  b->UseRealTime()->Unit(benchmark::kMicrosecond);
  // The fastest repetition: on a shared machine the least disturbed one (noise only adds time).
  b->ComputeStatistics("min", [](const std::vector<double>& v) {
    return v.empty() ? 0.0 : *std::min_element(v.begin(), v.end());
  });
}

void start_servers() {
  // Processes first, while this process has no ZeroMQ context.
  std::strcpy(g_ipc_dir, "/tmp/rockcut-bench-XXXXXX");
  if (mkdtemp(g_ipc_dir) == nullptr) {
    g_ipc_dir[0] = '\0';
    throw std::runtime_error(std::string("mkdtemp: ") + std::strerror(errno));
  }
  const std::vector<int> ports = free_tcp_ports(2);
  int port_index = 0;
  for (Transport t : {Transport::ipc, Transport::tcp}) {
    for (Encoding e : {Encoding::raw, Encoding::packed}) {
      auto link = std::make_unique<Link>();
      link->transport = t;
      link->encoding = e;
      if (t == Transport::ipc) {
        char* file = g_ipc_files[e == Encoding::raw ? 0 : 1];
        std::snprintf(file, sizeof g_ipc_files[0], "%s/%s.sock", g_ipc_dir, name_of(e));
        link->endpoint = std::string("ipc://") + file;
      } else {
        link->endpoint = "tcp://127.0.0.1:" + std::to_string(ports[port_index++]);
      }
      link->pid = fork_server(e, link->endpoint);
      g_links.push_back(std::move(link));
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> defaults;
  for (const char* flag : kDefaultFlags) {
    const std::string_view name(flag, std::strchr(flag, '=') - flag);
    bool given = false;
    for (int i = 1; i < argc; ++i) given |= std::string_view(argv[i]).starts_with(name);
    if (!given) defaults.emplace_back(flag);
  }
  std::vector<char*> args(argv, argv + argc);
  for (std::string& d : defaults) args.push_back(d.data());
  int arg_count = static_cast<int>(args.size());
  args.push_back(nullptr);
  benchmark::Initialize(&arg_count, args.data());
  if (benchmark::ReportUnrecognizedArguments(arg_count, args.data())) return 1;

  try {
    start_servers();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_exchange: %s\n", e.what());
    at_exit();
    return 1;
  }
  std::atexit(at_exit);
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaction(sig, &sa, nullptr);

  int code = 0;
  {
    zmq::context_t context(1);
    for (Encoding e : {Encoding::raw, Encoding::packed}) {
      auto link = std::make_unique<Link>();
      link->transport = Transport::inproc;
      link->encoding = e;
      link->endpoint = std::string("inproc://bench-exchange-") + name_of(e);
      link->thread = std::thread([&context, e, endpoint = link->endpoint] {
        try {
          run_server(context, e, endpoint);
        } catch (const std::exception&) {
          // context.shutdown() at exit, or a bind error the client then reports.
        }
      });
      g_links.insert(g_links.begin() + (e == Encoding::raw ? 0 : 1), std::move(link));
    }
    for (auto& link : g_links) {
      try {
        link->connect(context);
      } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_exchange: %s: %s\n", link->label().c_str(), e.what());
        link->stop();
        code = 1;
      }
    }

    if (code == 0) {
      configure(benchmark::RegisterBenchmark("baseline/memcpy", BM_Memcpy));
      configure(benchmark::RegisterBenchmark("baseline/kernel", BM_Kernel));
      for (Transport t : {Transport::inproc, Transport::ipc, Transport::tcp}) {
        for (Encoding e : {Encoding::raw, Encoding::packed}) {
          const std::string name = std::string("exchange/") + name_of(t) + "/" + name_of(e);
          configure(benchmark::RegisterBenchmark(name.c_str(), BM_Exchange, t, e));
        }
      }
      benchmark::RunSpecifiedBenchmarks();
    }

    for (auto& link : g_links) link->stop();
    context.shutdown();  // releases an inproc server that did not get the Shutdown
    for (auto& link : g_links) {
      if (link->thread.joinable()) link->thread.join();
      link->reap();
    }
    g_links.clear();
  }
  benchmark::Shutdown();
  kill_children();
  remove_ipc_dir();
  return code;
}
