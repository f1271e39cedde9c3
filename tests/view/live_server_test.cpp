// The live viewer's HTTP server, spoken to over a socket as a browser would.
#include "edgevio/view/live_server.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <thread>
#include <string>

#include "common/test_support.h"
#include "edgevio/common/error.h"

namespace edgevio::view {
namespace {

/// Sends `request` to 127.0.0.1:port and reads until the server closes or
/// `until` appears (or 5 s pass).
std::string exchange(int port, const std::string& request, const std::string& until = "") {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  EXPECT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  EXPECT_EQ(::send(fd, request.data(), request.size(), MSG_NOSIGNAL), static_cast<ssize_t>(request.size()));
  std::string got;
  char buf[4096];
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (std::chrono::steady_clock::now() < deadline && (until.empty() || got.find(until) == std::string::npos)) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 100) <= 0) continue;
    const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
    if (n <= 0) break;
    got.append(buf, static_cast<std::size_t>(n));
  }
  ::close(fd);
  return got;
}

TEST(LiveServer, ServesThePageAndNothingElse) {
  LiveServer server(0, "<html>the page</html>");
  ASSERT_GT(server.port(), 0);
  const std::string page = exchange(server.port(), "GET / HTTP/1.1\r\nHost: x\r\n\r\n");
  test::expectContainsAll(page, {"HTTP/1.1 200 OK", "text/html", "Content-Length: 21", "<html>the page</html>"});
  test::expectContainsAll(exchange(server.port(), "GET /secret HTTP/1.1\r\n\r\n"), {"404"});
}

TEST(LiveServer, StreamsEventsAndReplaysTheKeptOnesToALateBrowser) {
  LiveServer server(0, "page");
  server.publish("{\"n\": 1, \"picture\": \"big\"}", "{\"n\": 1}");
  // A browser connecting now gets the kept version of what it missed...
  const std::string late = exchange(server.port(), "GET /events HTTP/1.1\r\n\r\n", "data: {\"n\": 1}\n\n");
  test::expectContainsAll(late, {"text/event-stream", "data: {\"n\": 1}\n\n"});
  EXPECT_EQ(late.find("big"), std::string::npos);
  // ...and a multi-line event arrives as one event of several data lines, then the end.
  server.publish("{\n\"n\": 2\n}", "{\n\"n\": 2\n}");
  std::string stream;
  std::thread reader([&] { stream = exchange(server.port(), "GET /events HTTP/1.1\r\n\r\n", "event: end"); });
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  server.finish();
  reader.join();
  test::expectContainsAll(stream, {"data: {\ndata: \"n\": 2\ndata: }\n\n", "event: end\ndata: {}\n\n"});
}

TEST(LiveServer, APortInUseIsAnErrorThatSaysWhatToDo) {
  LiveServer first(0, "page");
  test::expectInputError([&] { LiveServer second(first.port(), "page"); }, {"cannot listen", "choose another port"});
  test::expectInputError([] { LiveServer bad(70000, "page"); }, {"not a TCP port"});
}

}  // namespace
}  // namespace edgevio::view
