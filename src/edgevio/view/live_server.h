#pragma once
// `edgevio run --view PORT`: the viewer's page served on localhost while the
// run goes, each frame streamed to it as a server-sent event (the page's
// /events, text/event-stream). A minimal HTTP/1.1 server on one thread of
// its own: the run's thread only queues events, so a slow or absent browser
// never holds up the estimator. A browser that connects late first gets
// every frame's record so far (the pictures only from when it connected:
// they are not kept, so memory stays small on long runs).
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace edgevio::view {

class LiveServer {
 public:
  /// Listens on 127.0.0.1:`port` (0: a free port) and serves `page` at /.
  /// Throws InputError when the port cannot be opened.
  LiveServer(int port, std::string page);
  ~LiveServer();
  LiveServer(const LiveServer&) = delete;
  LiveServer& operator=(const LiveServer&) = delete;

  int port() const { return port_; }

  /// Queues one event (JSON, one object) for every browser: `kept` is what a
  /// browser connecting later gets instead (e.g. the event without its picture).
  void publish(const std::string& json, const std::string& kept);
  /// Sends the end of the stream to every browser, waits (at most a few
  /// seconds) until they have it, and stops serving.
  void finish();

 private:
  struct Client {
    int fd = -1;
    std::size_t next = 0;  ///< the next event of `events_` to send
    std::string pending;   ///< bytes written only in part
  };
  void serve();
  void accept();
  void flush(Client& c);

  std::string page_;
  int listen_fd_ = -1;
  int port_ = 0;
  std::thread thread_;
  std::mutex mutex_;
  std::vector<std::string> events_;  ///< the stream, as sent to connected browsers
  std::vector<std::string> kept_;    ///< the stream, as replayed to late ones
  std::vector<Client> clients_;      ///< server thread only
  bool finishing_ = false;
};

}  // namespace edgevio::view
