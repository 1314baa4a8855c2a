// Running the `tem` program (TEM_BINARY) from tests as a user would: to completion, capturing
// stdout and stderr, or in the background, to interrupt it.
#pragma once

#include <gtest/gtest.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace tem::testing_support {

struct TemRun {
  int status = -1;  // exit status, or 128 + the signal that ended it
  std::string out;
  std::string err;
};

inline std::string slurp(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

inline int exit_status(int raw) {
  if (WIFEXITED(raw)) return WEXITSTATUS(raw);
  if (WIFSIGNALED(raw)) return 128 + WTERMSIG(raw);
  return -1;
}

// A temporary file name unique to this process and `tag` (ctest runs tests in parallel).
inline std::string temp_path(const std::string& tag) {
  return testing::TempDir() + "tem_" + tag + "_" + std::to_string(getpid());
}

// Runs `tem ARGS` through the shell, capturing stdout and stderr separately.
inline TemRun run_tem(const std::string& args) {
  const std::string out = temp_path("run.out"), err = temp_path("run.err");
  std::ostringstream command;  // (a stream: GCC 12 warns falsely on "'" + std::string)
  command << "'" << TEM_BINARY << "' " << args << " >'" << out << "' 2>'" << err << "'";
  TemRun run;
  run.status = exit_status(std::system(command.str().c_str()));
  run.out = slurp(out);
  run.err = slurp(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return run;
}

// `tem ARGS...` started in the background, stdout and stderr into files; wait() collects it.
class TemProcess {
 public:
  explicit TemProcess(const std::vector<std::string>& args)
      : out_(temp_path("bg.out")), err_(temp_path("bg.err")) {
    posix_spawn_file_actions_t files;
    posix_spawn_file_actions_init(&files);
    posix_spawn_file_actions_addopen(&files, 1, out_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&files, 2, err_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    std::vector<std::string> all{TEM_BINARY};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    if (posix_spawn(&pid_, TEM_BINARY, &files, nullptr, argv.data(), environ) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&files);
  }
  ~TemProcess() {
    if (pid_ > 0) {
      kill(pid_, SIGKILL);
      wait();
    }
  }
  TemProcess(const TemProcess&) = delete;
  TemProcess& operator=(const TemProcess&) = delete;

  bool started() const { return pid_ > 0; }
  void signal(int sig) const { kill(pid_, sig); }
  TemRun wait() {
    TemRun run;
    int raw = 0;
    if (pid_ > 0 && waitpid(pid_, &raw, 0) == pid_) run.status = exit_status(raw);
    pid_ = -1;
    run.out = slurp(out_);
    run.err = slurp(err_);
    std::filesystem::remove(out_);
    std::filesystem::remove(err_);
    return run;
  }

 private:
  pid_t pid_ = -1;
  std::string out_, err_;
};

}  // namespace tem::testing_support
