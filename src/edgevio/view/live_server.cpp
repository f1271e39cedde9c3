#include "edgevio/view/live_server.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>

#include "edgevio/common/error.h"

namespace edgevio::view {

namespace {

constexpr int kPollMs = 20;            // how soon a queued event leaves (and a finish is noticed)
constexpr int kFinishTimeoutMs = 3000;  // a browser that cannot take the end of the stream by then is dropped
constexpr std::size_t kMaxRequestBytes = 8192;

/// A server-sent event: every line of the JSON prefixed with "data: ", a blank line after.
std::string sse(const std::string& json, const char* event = nullptr) {
  std::string out = event ? std::string("event: ") + event + "\n" : std::string();
  std::size_t start = 0;
  while (start <= json.size()) {
    const std::size_t nl = json.find('\n', start);
    out += "data: " + json.substr(start, nl == std::string::npos ? std::string::npos : nl - start) + "\n";
    if (nl == std::string::npos) break;
    start = nl + 1;
  }
  return out + "\n";
}

std::string response(const char* status, const char* type, const std::string& body) {
  return std::string("HTTP/1.1 ") + status + "\r\nContent-Type: " + type + "\r\nContent-Length: " + std::to_string(body.size()) +
         "\r\nCache-Control: no-store\r\nConnection: close\r\n\r\n" + body;
}

/// Writes what the socket takes now; returns false when the browser is gone.
bool sendSome(int fd, std::string* bytes) {
  while (!bytes->empty()) {
    const ssize_t n = ::send(fd, bytes->data(), bytes->size(), MSG_NOSIGNAL | MSG_DONTWAIT);
    if (n > 0) {
      bytes->erase(0, static_cast<std::size_t>(n));
    } else if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
      return true;
    } else if (n < 0 && errno == EINTR) {
      continue;
    } else {
      return false;
    }
  }
  return true;
}

/// Reads an HTTP request's head (blocking, the browser sends it at once); its path, or "" when there is none.
std::string requestPath(int fd) {
  std::string head;
  char buf[1024];
  while (head.find("\r\n\r\n") == std::string::npos && head.size() < kMaxRequestBytes) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 2000) <= 0) return "";
    const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
    if (n <= 0) return "";
    head.append(buf, static_cast<std::size_t>(n));
  }
  if (head.compare(0, 4, "GET ") != 0) return "";
  const std::size_t end = head.find(' ', 4);
  return end == std::string::npos ? "" : head.substr(4, end - 4);
}

}  // namespace

LiveServer::LiveServer(int port, std::string page) : page_(std::move(page)) {
  if (port < 0 || port > 65535) throw InputError("--view: port " + std::to_string(port) + " is not a TCP port (0-65535; 0: any free one)");
  listen_fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
  if (listen_fd_ < 0) throw InputError(std::string("--view: cannot open a socket: ") + std::strerror(errno));
  const int yes = 1;
  ::setsockopt(listen_fd_, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);  // localhost only: the page shows the run to this machine
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  if (::bind(listen_fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 || ::listen(listen_fd_, 8) != 0) {
    const std::string why = std::strerror(errno);
    ::close(listen_fd_);
    throw InputError("--view: cannot listen on 127.0.0.1:" + std::to_string(port) + ": " + why + " (choose another port, or 0)");
  }
  socklen_t len = sizeof addr;
  ::getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&addr), &len);
  port_ = ntohs(addr.sin_port);
  thread_ = std::thread([this] { serve(); });
}

LiveServer::~LiveServer() {
  finish();
  if (listen_fd_ >= 0) ::close(listen_fd_);
}

void LiveServer::publish(const std::string& json, const std::string& kept) {
  const std::lock_guard<std::mutex> lock(mutex_);
  events_.push_back(sse(json));
  kept_.push_back(sse(kept));
}

void LiveServer::finish() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (finishing_) return;
    const std::string end = sse("{}", "end");
    events_.push_back(end);
    kept_.push_back(end);
    finishing_ = true;
  }
  if (thread_.joinable()) thread_.join();
}

void LiveServer::accept() {
  const int fd = ::accept(listen_fd_, nullptr, nullptr);
  if (fd < 0) return;
  const std::string path = requestPath(fd);
  if (path == "/events") {
    std::string head = "HTTP/1.1 200 OK\r\nContent-Type: text/event-stream\r\nCache-Control: no-store\r\nConnection: keep-alive\r\n\r\n";
    Client c{fd, 0, std::move(head)};
    {
      // A late browser first gets the stream so far, without the pictures.
      const std::lock_guard<std::mutex> lock(mutex_);
      for (; c.next < kept_.size(); ++c.next) c.pending += kept_[c.next];
    }
    clients_.push_back(std::move(c));
    return;
  }
  std::string reply = path == "/" || path == "/index.html" ? response("200 OK", "text/html; charset=utf-8", page_)
                                                          : response("404 Not Found", "text/plain", "edgevio serves / and /events\n");
  // The page is sent whole (blocking, with a bound): it is the only other request.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(kFinishTimeoutMs);
  while (!reply.empty() && std::chrono::steady_clock::now() < deadline) {
    if (!sendSome(fd, &reply)) break;
    pollfd p{fd, POLLOUT, 0};
    ::poll(&p, 1, kPollMs);
  }
  ::close(fd);
}

void LiveServer::flush(Client& c) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (; c.next < events_.size(); ++c.next) c.pending += events_[c.next];
  }
  if (!sendSome(c.fd, &c.pending)) {
    ::close(c.fd);
    c.fd = -1;
  }
}

void LiveServer::serve() {
  std::chrono::steady_clock::time_point finish_deadline{};
  for (;;) {
    bool finishing;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      finishing = finishing_;
    }
    if (finishing && finish_deadline == std::chrono::steady_clock::time_point{})
      finish_deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(kFinishTimeoutMs);
    pollfd p{listen_fd_, POLLIN, 0};
    if (!finishing && ::poll(&p, 1, kPollMs) > 0) accept();
    if (finishing) ::poll(nullptr, 0, kPollMs);
    for (Client& c : clients_) flush(c);
    clients_.erase(std::remove_if(clients_.begin(), clients_.end(), [](const Client& c) { return c.fd < 0; }), clients_.end());
    if (finishing) {
      std::size_t total;
      {
        const std::lock_guard<std::mutex> lock(mutex_);
        total = events_.size();
      }
      const bool all_sent = std::all_of(clients_.begin(), clients_.end(), [&](const Client& c) { return c.next == total && c.pending.empty(); });
      if (all_sent || std::chrono::steady_clock::now() > finish_deadline) break;
    }
  }
  for (Client& c : clients_) ::close(c.fd);
  clients_.clear();
}

}  // namespace edgevio::view
