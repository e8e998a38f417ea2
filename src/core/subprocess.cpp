#include "relief/core/subprocess.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "relief/core/errors.h"

extern char** environ;  // NOLINT(readability-redundant-declaration): glibc declares it only with _GNU_SOURCE

namespace relief {
namespace {

bool is_executable(const std::filesystem::path& p) {
  std::error_code ec;
  return std::filesystem::is_regular_file(p, ec) && ::access(p.c_str(), X_OK) == 0;
}

}  // namespace

std::optional<std::filesystem::path> find_executable(std::string_view name,
                                                     const std::vector<std::filesystem::path>& extra_dirs) {
  if (name.find('/') != std::string_view::npos) {
    const std::filesystem::path p(name);
    return is_executable(p) ? std::optional(p) : std::nullopt;
  }
  for (const auto& dir : extra_dirs) {
    if (is_executable(dir / name)) return dir / name;
  }
  const char* path = std::getenv("PATH");
  std::string_view rest = path ? path : "/usr/local/bin:/usr/bin:/bin";
  while (!rest.empty()) {
    const std::size_t colon = rest.find(':');
    const std::string_view dir = rest.substr(0, colon);
    if (!dir.empty() && is_executable(std::filesystem::path(dir) / name))
      return std::filesystem::path(dir) / name;
    if (colon == std::string_view::npos) break;
    rest.remove_prefix(colon + 1);
  }
  return std::nullopt;
}

ProcessResult run_process(const std::vector<std::string>& argv, const Environment& env,
                          const std::optional<std::filesystem::path>& working_dir) {
  if (argv.empty()) throw InvalidInput("run_process: no program given");
  const auto program = find_executable(argv[0]);
  if (!program) throw IoError("cannot run '" + argv[0] + "': not found on PATH");

  // stdout and stderr go to one pipe that the parent drains until the child closes it.
  std::array<int, 2> pipe_fd{};
  if (::pipe2(pipe_fd.data(), O_CLOEXEC) != 0)
    throw IoError("cannot run '" + argv[0] + "': " + std::strerror(errno));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_fd[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, pipe_fd[1], STDERR_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  if (working_dir) posix_spawn_file_actions_addchdir_np(&actions, working_dir->c_str());

  // The child's environment: ours with `env` replacing or adding variables.
  std::vector<std::string> env_text;
  for (char** e = environ; *e; ++e) {
    const std::string_view entry(*e);
    const bool replaced = std::any_of(env.begin(), env.end(), [&](const auto& kv) {
      return entry.size() > kv.first.size() && entry.compare(0, kv.first.size(), kv.first) == 0 &&
             entry[kv.first.size()] == '=';
    });
    if (!replaced) env_text.emplace_back(entry);
  }
  for (const auto& [key, value] : env) env_text.push_back(key + "=" + value);
  std::vector<char*> envp;
  envp.reserve(env_text.size() + 1);
  for (std::string& e : env_text) envp.push_back(e.data());
  envp.push_back(nullptr);

  std::vector<char*> args;
  args.reserve(argv.size() + 1);
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, program->c_str(), &actions, nullptr, args.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  ::close(pipe_fd[1]);
  if (rc != 0) {
    ::close(pipe_fd[0]);
    throw IoError("cannot run '" + program->string() + "': " + std::strerror(rc));
  }

  ProcessResult result;
  std::array<char, 65536> buffer{};
  for (;;) {
    const ssize_t n = ::read(pipe_fd[0], buffer.data(), buffer.size());
    if (n > 0) {
      result.output.append(buffer.data(), static_cast<std::size_t>(n));
    } else if (n == 0 || errno != EINTR) {
      break;
    }
  }
  ::close(pipe_fd[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return result;
}

}  // namespace relief
