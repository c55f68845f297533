// Functions run in a forked child (io/ChildProcess.h's runForked): what one sends arrives whole, a
// throw comes back as its message, a death as its signal, and nothing the child changes reaches
// the parent.
#include "io/ChildProcess.h"
#include "io/Error.h"

#include <gtest/gtest.h>

#include <csignal>
#include <numeric>
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

}  // namespace
}  // namespace jawmesh
