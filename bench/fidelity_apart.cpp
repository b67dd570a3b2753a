/*
 * fidelity_apart.cpp - the apart side's worker process and the pipes to it
 * (fidelity_apart.h).
 */
#include "fidelity_apart.h"

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <iostream>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

namespace mpb_fidelity {

ApartProcess::~ApartProcess()
{
    if (to_ >= 0)
        close(to_);
    if (from_ >= 0)
        close(from_);
    if (pid_ > 0) {
        int status;
        while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
        }
    }
}

bool ApartProcess::start(const std::vector<std::string> &args)
{
    int in[2], out[2];      // the worker's standard input and output
    if (pipe2(in, O_CLOEXEC) != 0)
        return std::perror("mpb-bench-fidelity: pipe"), false;
    if (pipe2(out, O_CLOEXEC) != 0) {
        close(in[0]);
        close(in[1]);
        return std::perror("mpb-bench-fidelity: pipe"), false;
    }
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_adddup2(&fa, in[0], STDIN_FILENO);
    posix_spawn_file_actions_adddup2(&fa, out[1], STDOUT_FILENO);
    std::vector<char *> argv;
    static char self[] = "/proc/self/exe";
    argv.push_back(self);
    for (const std::string &a : args)
        argv.push_back(const_cast<char *>(a.c_str()));
    argv.push_back(nullptr);
    int rc = posix_spawn(&pid_, self, &fa, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&fa);
    close(in[0]);
    close(out[1]);
    to_ = in[1];
    from_ = out[0];
    if (rc != 0) {
        pid_ = -1;
        std::fprintf(stderr, "mpb-bench-fidelity: cannot start the apart worker: %s\n",
                     std::strerror(rc));
        return false;
    }
    // A worker that dies must not end this process with SIGPIPE.
    std::signal(SIGPIPE, SIG_IGN);
    return true;
}

bool ApartProcess::ask(const std::string &seed, std::string *answer)
{
    std::string line = seed + "\n";
    for (size_t off = 0; off < line.size();) {
        ssize_t n = write(to_, line.data() + off, line.size() - off);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0) {
            std::fprintf(stderr, "mpb-bench-fidelity: the apart worker is gone\n");
            return false;
        }
        off += static_cast<size_t>(n);
    }
    // Blocks here, as the planner's benchmark blocks for its result.
    for (;;) {
        size_t nl = pending_.find('\n');
        if (nl != std::string::npos) {
            *answer = pending_.substr(0, nl);
            pending_.erase(0, nl + 1);
            return true;
        }
        char buf[256];
        ssize_t n = read(from_, buf, sizeof buf);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0) {
            std::fprintf(stderr, "mpb-bench-fidelity: the apart worker is gone\n");
            return false;
        }
        pending_.append(buf, static_cast<size_t>(n));
    }
}

int apart_serve(const std::function<std::string(const std::string &seed)> &answer)
{
    std::string seed;
    while (std::getline(std::cin, seed)) {
        std::string a = answer(seed) + "\n";
        if (std::fwrite(a.data(), 1, a.size(), stdout) != a.size() || std::fflush(stdout) != 0)
            return 1;
    }
    return 0;
}

} // namespace mpb_fidelity
