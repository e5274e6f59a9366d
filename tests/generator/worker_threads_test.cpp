#include "wrc/generator/worker_threads.h"

#include <gtest/gtest.h>
#include <pthread.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace wrc::gen {
namespace {

constexpr int kItems = 1000;
constexpr int kAskedFor = 64;

// Every item of a shared queue, taken by however many workers started.
int RunQueue(int* started) {
  std::atomic<int> next{0}, done{0};
  WorkerThreads pool(
      kAskedFor,
      [&] {
        for (int k = next++; k < kItems; k = next++) ++done;
      },
      "test pool");
  *started = pool.started();
  pool.Join();
  return done.load();
}

// The process's mapped size in bytes (first field of /proc/self/statm, in pages).
long MappedBytes() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0;
  statm >> pages;
  return pages * sysconf(_SC_PAGESIZE);
}

struct ChildOutcome {
  int exit_code = -1;
  std::string err;
};

constexpr long kStack = 64L << 20;

// Runs RunQueue in a child whose address space may grow by `headroom` bytes: each thread's stack
// (kStack, larger than the stacks glibc keeps cached from earlier threads, so that each new
// thread maps a new one) must fit in it, and the system refuses threads once it is used up.
// Exit codes: 0 every item done, 1 items lost, 2 the constructor threw, 3 more threads than fit.
ChildOutcome RunWithHeadroom(long headroom) {
  char err_path[] = "/tmp/wrc_worker_threads_XXXXXX";
  const int err_fd = mkstemp(err_path);
  if (err_fd < 0) return {};
  const pid_t child = fork();
  if (child == 0) {
    dup2(err_fd, 2);
    pthread_attr_t attr;
    pthread_attr_init(&attr);
    pthread_attr_setstacksize(&attr, kStack);
    pthread_setattr_default_np(&attr);
    const long limit = MappedBytes() + headroom;
    const rlimit as{static_cast<rlim_t>(limit), static_cast<rlim_t>(limit)};
    setrlimit(RLIMIT_AS, &as);
    try {
      int started = 0;
      const int done = RunQueue(&started);
      std::fprintf(stderr, "\nstarted=%d\n", started);
      _exit(done != kItems ? 1 : started >= kAskedFor ? 3 : 0);
    } catch (const std::runtime_error& e) {
      std::fprintf(stderr, "%s\n", e.what());
      _exit(2);
    }
  }
  int status = 0;
  waitpid(child, &status, 0);
  std::ifstream in(err_path);
  std::stringstream text;
  text << in.rdbuf();
  close(err_fd);
  unlink(err_path);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), text.str()};
}

TEST(WorkerThreads, AllAskedForStartAndTakeTheWholeQueue) {
  int started = 0;
  EXPECT_EQ(RunQueue(&started), kItems);
  EXPECT_EQ(started, kAskedFor);
}

TEST(WorkerThreads, AnExceptionFromABodyIsRethrownByJoinAndTheOthersFinish) {
  std::atomic<int> next{0}, done{0};
  WorkerThreads pool(
      4,
      [&] {
        for (int k = next++; k < kItems; k = next++) {
          if (k == 10) throw std::runtime_error("item 10 failed");
          ++done;
        }
      },
      "test pool");
  try {
    pool.Join();
    ADD_FAILURE() << "Join did not rethrow";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "item 10 failed");
  }
  EXPECT_EQ(done.load(), kItems - 1);  // the other threads took the rest of the queue
  EXPECT_NO_THROW(pool.Join());        // rethrown once
}

TEST(WorkerThreads, ThreadsTheSystemRefusesLeaveTheWorkToTheOthersAndAWarning) {
  // Room for two or three stacks, not for 64.
  const ChildOutcome outcome = RunWithHeadroom(3 * kStack);
  EXPECT_EQ(outcome.exit_code, 0) << outcome.err;
  EXPECT_NE(outcome.err.find("warning: test pool: the system started"), std::string::npos)
      << outcome.err;
  EXPECT_NE(outcome.err.find("of 64 worker threads"), std::string::npos) << outcome.err;
}

TEST(WorkerThreads, NoThreadAtAllIsAnErrorInWords) {
  const ChildOutcome outcome = RunWithHeadroom(1L << 20);
  EXPECT_EQ(outcome.exit_code, 2) << outcome.err;
  EXPECT_NE(outcome.err.find("test pool: the system refused to start a worker thread"),
            std::string::npos)
      << outcome.err;
}

}  // namespace
}  // namespace wrc::gen
