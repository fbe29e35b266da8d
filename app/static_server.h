#pragma once
// A minimal HTTP/1.0 file server on 127.0.0.1 for the viewer page (`phedra
// view`): GET only, files under one root, a fixed set of extra files (the
// model), no directory listings, no path outside the root.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <string>

namespace phedra::cli {

class StaticServer {
 public:
  /// Binds 127.0.0.1:port (0: any free port). IOError when it cannot.
  StaticServer(std::filesystem::path root, std::uint16_t port);
  ~StaticServer();
  StaticServer(const StaticServer&) = delete;
  StaticServer& operator=(const StaticServer&) = delete;

  std::uint16_t port() const { return port_; }
  /// Serves `file` at `url_path` (for example "/model.glb").
  void add_file(const std::string& url_path, std::filesystem::path file);
  /// Serves what `make()` returns at `url_path`, made when asked for (an
  /// exception it throws answers 500 with its message), as `mime`.
  void add_generated(const std::string& url_path, std::function<std::string()> make, std::string mime);
  /// Serves requests until `keep_going()` returns false (checked between requests)
  /// or `max_requests` were answered (0: no limit).
  void serve(std::size_t max_requests = 0);

 private:
  void answer(int client);
  std::filesystem::path root_;
  std::map<std::string, std::filesystem::path> files_;
  std::map<std::string, std::pair<std::function<std::string()>, std::string>> generated_;
  int socket_ = -1;
  std::uint16_t port_ = 0;
};

}  // namespace phedra::cli
