// SPDX-License-Identifier: GPL-3.0-or-later
// shrink_solids: the 3D route in a child process, so that TetGen's crashes and endless loops
// on faces of real data cost one building its occluders instead of the whole bake.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
#include <string>

#include "urbanpvs/geometry/occluders/SolidOccluders.hpp"

namespace urbanpvs::geometry {
namespace {

// A result goes through the pipe as: its byte count (u64), then the input's index (u64), the
// exterior tetrahedra (u64), the reason it was declined (u64 length, bytes), the occluders
// (u64 count; each its top (f64) and rings (u64 count; each u64 points, then x, y as f64)).
class RecordWriter {
 public:
  void u64(std::uint64_t v) { bytes(&v, sizeof v); }
  void f64(double v) { bytes(&v, sizeof v); }
  void bytes(const void* p, std::size_t n) {
    const auto* c = static_cast<const unsigned char*>(p);
    out_.insert(out_.end(), c, c + n);
  }
  std::vector<unsigned char>& data() { return out_; }

 private:
  std::vector<unsigned char> out_;
};

class RecordReader {
 public:
  RecordReader(const unsigned char* p, std::size_t n) : p_(p), end_(p + n) {}
  std::uint64_t u64() {
    std::uint64_t v = 0;
    bytes(&v, sizeof v);
    return v;
  }
  double f64() {
    double v = 0;
    bytes(&v, sizeof v);
    return v;
  }
  void bytes(void* out, std::size_t n) {
    if (static_cast<std::size_t>(end_ - p_) < n) {
      ok_ = false;
      std::memset(out, 0, n);
      return;
    }
    std::memcpy(out, p_, n);
    p_ += n;
  }
  bool ok() const { return ok_; }

 private:
  const unsigned char* p_;
  const unsigned char* end_;
  bool ok_ = true;
};

void write_ring(RecordWriter& w, const Ring& r) {
  w.u64(r.size());
  for (const Vec2& p : r) {
    w.f64(p.x);
    w.f64(p.y);
  }
}

std::vector<unsigned char> encode(std::size_t index, const ShrunkSolid& s) {
  RecordWriter w;
  w.u64(0);  // the byte count, set below
  w.u64(index);
  w.u64(s.exterior_tetrahedra);
  w.u64(s.declined.size());
  w.bytes(s.declined.data(), s.declined.size());
  w.u64(s.occluders.size());
  for (const Occluder& o : s.occluders) {
    w.f64(o.top_z);
    w.u64(1 + o.shape.holes.size());
    write_ring(w, o.shape.outer);
    for (const Ring& h : o.shape.holes) write_ring(w, h);
  }
  const std::uint64_t size = w.data().size() - sizeof(std::uint64_t);
  std::memcpy(w.data().data(), &size, sizeof size);
  return std::move(w.data());
}

Ring read_ring(RecordReader& r) {
  Ring ring(static_cast<std::size_t>(r.u64()));
  for (Vec2& p : ring) {
    p.x = r.f64();
    p.y = r.f64();
  }
  return ring;
}

bool decode(const unsigned char* p, std::size_t n, std::size_t& index, ShrunkSolid& s) {
  RecordReader r(p, n);
  index = static_cast<std::size_t>(r.u64());
  s.exterior_tetrahedra = static_cast<std::size_t>(r.u64());
  s.declined.resize(static_cast<std::size_t>(r.u64()));
  r.bytes(s.declined.data(), s.declined.size());
  const std::uint64_t count = r.u64();
  for (std::uint64_t k = 0; k < count && r.ok(); ++k) {
    Occluder o;
    o.block = kSolidBlock;
    o.top_z = r.f64();
    const std::uint64_t rings = r.u64();
    for (std::uint64_t j = 0; j < rings && r.ok(); ++j)
      (j == 0 ? o.shape.outer : o.shape.holes.emplace_back()) = read_ring(r);
    o.bounds = bounds(o.shape);
    s.occluders.push_back(std::move(o));
  }
  return r.ok();
}

bool write_all(int fd, const std::vector<unsigned char>& data) {
  std::size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

/// The child: shrinks inputs[first, end) and writes each result; never returns.
[[noreturn]] void child(int fd, const std::vector<SolidInput>& inputs, std::size_t first,
                        const std::function<ShrunkSolid(const SolidInput&)>& shrink) {
  // TetGen's assertions and messages would land in the bake's own output; the parent reports
  // what became of each building.
  const int null = ::open("/dev/null", O_WRONLY);
  if (null >= 0) {
    ::dup2(null, STDOUT_FILENO);
    ::dup2(null, STDERR_FILENO);
    ::close(null);
  }
  // Nothing may leave this function but _exit: an exception unwinding into the parent's code
  // would run the rest of the bake (or of a test suite, or MPI_Abort) a second time.
  try {
    for (std::size_t k = first; k < inputs.size(); ++k) {
      ShrunkSolid s;
      try {
        s = shrink(inputs[k]);
      } catch (const std::bad_alloc&) {
        s = {};
        s.declined = "the 3D route ran out of memory";
      } catch (const std::exception& e) {
        s = {};
        s.declined = std::string("the 3D route failed: ") + e.what();
      }
      if (!write_all(fd, encode(k, s))) break;
    }
  } catch (...) {
    ::_exit(3);
  }
  ::close(fd);
  ::_exit(0);  // no destructors, no atexit handlers: they belong to the parent
}

}  // namespace

std::vector<ShrunkSolid> shrink_solids(const std::vector<SolidInput>& inputs, double epsilon,
                                       double step, double seconds) {
  return shrink_solids(inputs, seconds, [&](const SolidInput& input) {
    return shrink_solid(*input.surfaces, input.ground_z, epsilon, step);
  });
}

std::vector<ShrunkSolid> shrink_solids(
    const std::vector<SolidInput>& inputs, double seconds,
    const std::function<ShrunkSolid(const SolidInput&)>& shrink) {
  using Clock = std::chrono::steady_clock;
  std::vector<ShrunkSolid> results(inputs.size());
  std::size_t next = 0;  // the first input without a result
  while (next < inputs.size()) {
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) {
      for (; next < inputs.size(); ++next) results[next].declined = "no pipe for the TetGen child";
      break;
    }
    const pid_t pid = ::fork();
    if (pid < 0) {
      ::close(fds[0]);
      ::close(fds[1]);
      for (; next < inputs.size(); ++next) results[next].declined = "no TetGen child process";
      break;
    }
    if (pid == 0) {
      ::close(fds[0]);
      child(fds[1], inputs, next, shrink);
    }
    ::close(fds[1]);
    std::vector<unsigned char> buffer;
    Clock::time_point started = Clock::now();  // on the input `next`
    bool timed_out = false, ended = false;
    for (;;) {
      const double left = seconds - std::chrono::duration<double>(Clock::now() - started).count();
      pollfd p{fds[0], POLLIN, 0};
      // What has arrived is read before the deadline is judged; a wait is at most a minute.
      const int wait_ms =
          left <= 0 ? 0 : static_cast<int>(std::min(60000.0, std::ceil(left * 1000)));
      const int ready = ::poll(&p, 1, wait_ms);
      if (ready < 0 && errno == EINTR) continue;
      if (ready == 0) {
        if (left <= 0) {
          timed_out = true;
          break;
        }
        continue;
      }
      unsigned char chunk[65536];
      const ssize_t n = ::read(fds[0], chunk, sizeof chunk);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        ended = n == 0;  // the child is done, or died; a read error leaves it to be killed
        break;
      }
      buffer.insert(buffer.end(), chunk, chunk + n);
      // Every complete record.
      std::size_t at = 0;
      while (buffer.size() - at >= sizeof(std::uint64_t)) {
        std::uint64_t size = 0;
        std::memcpy(&size, buffer.data() + at, sizeof size);
        if (buffer.size() - at - sizeof size < size) break;
        std::size_t index = 0;
        ShrunkSolid s;
        if (decode(buffer.data() + at + sizeof size, static_cast<std::size_t>(size), index, s) &&
            index == next) {
          results[next++] = std::move(s);
          started = Clock::now();
        }
        at += sizeof size + static_cast<std::size_t>(size);
      }
      buffer.erase(buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(at));
    }
    ::close(fds[0]);
    if (!ended) ::kill(pid, SIGKILL);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (next < inputs.size()) {
      // The child stopped on input `next`: it gives nothing, and a new child takes the rest.
      char why[96];
      if (timed_out)
        std::snprintf(why, sizeof why,
                      "the 3D route took longer than %.0f s (TetGen 1.5 loops on some faces)",
                      seconds);
      else
        std::snprintf(why, sizeof why,
                      "the 3D route crashed on its faces (TetGen 1.5 does on some)");
      results[next++].declined = why;
    }
  }
  return results;
}

}  // namespace urbanpvs::geometry
