#include "static_server.h"

#include "phedra/errors.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstring>
#include <fstream>
#include <sstream>

namespace phedra::cli {
namespace {

std::string mime_type(const std::filesystem::path& file) {
  static const std::map<std::string, std::string> types{
      {".html", "text/html; charset=utf-8"}, {".js", "text/javascript"},  {".mjs", "text/javascript"},
      {".css", "text/css"},                  {".json", "application/json"}, {".glb", "model/gltf-binary"},
      {".gltf", "model/gltf+json"},          {".png", "image/png"},       {".svg", "image/svg+xml"},
      {".wasm", "application/wasm"}};
  const auto it = types.find(file.extension().string());
  return it == types.end() ? "application/octet-stream" : it->second;
}

void send_all(int client, const std::string& data) {
  std::size_t sent = 0;
  while (sent < data.size()) {
    const ssize_t n = ::send(client, data.data() + sent, data.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) return;
    sent += static_cast<std::size_t>(n);
  }
}

void respond(int client, int status, const std::string& reason, const std::string& type, const std::string& body) {
  std::ostringstream head;
  head << "HTTP/1.0 " << status << ' ' << reason << "\r\nContent-Type: " << type
       << "\r\nContent-Length: " << body.size() << "\r\nCache-Control: no-store\r\nConnection: close\r\n\r\n";
  send_all(client, head.str() + body);
}

}  // namespace

StaticServer::StaticServer(std::filesystem::path root, std::uint16_t port) : root_(std::move(root)) {
  socket_ = ::socket(AF_INET, SOCK_STREAM, 0);
  if (socket_ < 0) throw IOError("view: cannot create a socket");
  const int yes = 1;
  ::setsockopt(socket_, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(port);
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::bind(socket_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 || ::listen(socket_, 16) != 0) {
    ::close(socket_);
    throw IOError("view: cannot listen on 127.0.0.1:" + std::to_string(port) + ": " + std::strerror(errno));
  }
  socklen_t length = sizeof address;
  ::getsockname(socket_, reinterpret_cast<sockaddr*>(&address), &length);
  port_ = ntohs(address.sin_port);
}

StaticServer::~StaticServer() {
  if (socket_ >= 0) ::close(socket_);
}

void StaticServer::add_file(const std::string& url_path, std::filesystem::path file) { files_[url_path] = std::move(file); }

void StaticServer::add_generated(const std::string& url_path, std::function<std::string()> make, std::string mime) {
  generated_[url_path] = {std::move(make), std::move(mime)};
}

void StaticServer::serve(std::size_t max_requests) {
  for (std::size_t answered = 0; max_requests == 0 || answered < max_requests; ++answered) {
    const int client = ::accept(socket_, nullptr, nullptr);
    if (client < 0) continue;
    answer(client);
    ::close(client);
  }
}

void StaticServer::answer(int client) {
  char buffer[8192];
  const ssize_t n = ::recv(client, buffer, sizeof buffer - 1, 0);
  if (n <= 0) return;
  buffer[n] = '\0';
  std::istringstream request(buffer);
  std::string method, target;
  request >> method >> target;
  if (method != "GET") return respond(client, 405, "Method Not Allowed", "text/plain", "GET only\n");
  target = target.substr(0, target.find('?'));
  if (target == "/") target = "/index.html";
  if (const auto it = generated_.find(target); it != generated_.end()) {
    std::string body;
    try {
      body = it->second.first();
    } catch (const std::exception& e) {
      return respond(client, 500, "Internal Server Error", "text/plain", std::string(e.what()) + "\n");
    }
    return respond(client, 200, "OK", it->second.second, body);
  }
  std::filesystem::path file;
  if (const auto it = files_.find(target); it != files_.end()) {
    file = it->second;
  } else {
    if (target.find("..") != std::string::npos) return respond(client, 403, "Forbidden", "text/plain", "no\n");
    file = root_ / target.substr(1);
  }
  std::ifstream in(file, std::ios::binary);
  if (!in || std::filesystem::is_directory(file)) return respond(client, 404, "Not Found", "text/plain", "not found\n");
  std::ostringstream body;
  body << in.rdbuf();
  respond(client, 200, "OK", mime_type(file), body.str());
}

}  // namespace phedra::cli
