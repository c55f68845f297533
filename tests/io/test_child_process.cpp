// Functions run in a forked child (io/ChildProcess.h's runForked): what one sends arrives whole, a
// throw comes back as its message, a death as its signal, and nothing the child changes reaches
// the parent.
#include "io/ChildProcess.h"
#include "io/Error.h"

#include <gtest/gtest.h>

#include <csignal>
#include <numeric>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace jawmesh {
namespace {

TEST(ChildProcess, ForkedFunctionSendsItsBytesItsErrorOrItsDeath) {
    std::vector<std::int64_t> sent(300000);  // more than a pipe holds: the parent reads while the child writes
    std::iota(sent.begin(), sent.end(), 7);
    bool changed = false;
    const ForkedResult ok = runForked([&](ParentPipe& pipe) {
        changed = true;
        sendToParent(pipe, sent.data(), sent.size());
    });
    EXPECT_FALSE(changed);
    EXPECT_TRUE(ok.returned);
    EXPECT_FALSE(ok.thrown);
    EXPECT_EQ(ok.exit.exitCode, 0);
    EXPECT_EQ(ok.exit.signal, 0);
    EXPECT_GT(ok.exit.peakMemoryBytes, 0u);
    std::vector<std::int64_t> received(sent.size());
    std::size_t at = 0;
    ASSERT_TRUE(takeFromChild(ok.bytes, at, received.data(), received.size()));
    EXPECT_EQ(at, ok.bytes.size());
    EXPECT_EQ(received, sent);
    std::int64_t more = 0;
    EXPECT_FALSE(takeFromChild(ok.bytes, at, &more, 1));

    const ForkedResult threw = runForked([](ParentPipe& pipe) {
        const int partial = 1;
        sendToParent(pipe, &partial, 1);
        throw Error("stage", "a reason");
    });
    EXPECT_FALSE(threw.returned);
    ASSERT_TRUE(threw.thrown);
    EXPECT_EQ(*threw.thrown, "stage: a reason");
    EXPECT_EQ(threw.bytes.size(), sizeof(int));  // what it sent before the throw

    const ForkedResult died = runForked([](ParentPipe&) { std::raise(SIGKILL); });
    EXPECT_EQ(died.exit.signal, SIGKILL);
    EXPECT_FALSE(died.returned);
    EXPECT_FALSE(died.thrown);
    EXPECT_NE(describeExit(died.exit).find("signal 9"), std::string::npos);
}

TEST(ChildProcess, StartedChildWorksWhileTheParentDoesAndAnUnfinishedOneIsKilled) {
    std::vector<std::int64_t> sent(300000);  // more than a pipe holds: the child waits until it is read
    std::iota(sent.begin(), sent.end(), -5);
    ForkedChild child = startForked([&](ParentPipe& pipe) { sendToParent(pipe, sent.data(), sent.size()); });
    ASSERT_GT(child.pid, 0);
    const std::int64_t parentsOwn = std::accumulate(sent.begin(), sent.end(), std::int64_t(0));
    const ForkedResult r = finishForked(child);
    EXPECT_EQ(child.pid, -1);
    EXPECT_TRUE(r.returned);
    std::vector<std::int64_t> received(sent.size());
    std::size_t at = 0;
    ASSERT_TRUE(takeFromChild(r.bytes, at, received.data(), received.size()));
    EXPECT_EQ(std::accumulate(received.begin(), received.end(), std::int64_t(0)), parentsOwn);

    int pid = 0;
    {
        ForkedChild forever = startForked([](ParentPipe&) {
            for (;;) ::pause();
        });
        pid = forever.pid;
        ForkedChild moved(std::move(forever));
        EXPECT_EQ(forever.pid, -1);
    }  // dropped unfinished: killed and reaped
    EXPECT_EQ(::waitpid(pid, nullptr, WNOHANG), -1);  // no such child left, not even a zombie
}

}  // namespace
}  // namespace jawmesh
