// phedra view FILE.glb [--port P]: serves the viewer page and the model on 127.0.0.1.

#include "buildability_warning.h"
#include "commands.h"
#include "phedra/errors.h"
#include "phedra/gltf_export.h"
#include "phedra/preset.h"
#include "static_server.h"
#include "support.h"
#include "phedra/files.h"
#include "phedra/design_preset.h"

#include <algorithm>
#include <filesystem>
#include <memory>
#include <ostream>

namespace phedra::cli {
namespace {

struct ViewOptions {
  std::string file;
  std::uint16_t port = 8765;
  std::string web = PHEDRA_WEB_DIR;
  std::string presets = PHEDRA_PRESETS_DIR;
  std::size_t requests = 0;
};

/// The presets for the pages' menus: /presets/index.json lists
/// [{file, name, description}]; each preset is at /presets/FILE and its default
/// glTF export at /presets/STEM.glb (made when the viewer asks for it).
void serve_presets(StaticServer& server, const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::vector<fs::path> files;
  if (fs::is_directory(dir)) {
    for (const auto& entry : fs::directory_iterator(dir)) {
      if (entry.is_regular_file() && entry.path().extension() == ".json" && entry.path().stem() != "preset.schema") {
        files.push_back(entry.path());
      }
    }
  }
  std::sort(files.begin(), files.end());
  nlohmann::json index = nlohmann::json::array();
  for (const fs::path& path : files) {
    nlohmann::json document;
    try {
      document = parse_json_text(read_text_file(path));
    } catch (const Error&) {
      continue;  // not readable as JSON: not listed
    }
    const std::string stem = path.stem().string();
    index.push_back({{"file", path.filename().string()},
                     {"name", document.is_object() ? document.value("name", stem) : stem},
                     {"description", document.is_object() ? document.value("description", "") : ""}});
    server.add_file("/presets/" + path.filename().string(), path);
    server.add_generated("/presets/" + stem + ".glb", [path] {
      const nlohmann::json shipped = parse_json_text(read_text_file(path));
      const Design design = design_from_json(shipped);
      GltfOptions options;
      options.buildability = assess_for_output(design).file_json();
      options.preset_text = preset_object(shipped).dump();
      return gltf_bytes(design, options);
    }, "model/gltf-binary");
  }
  server.add_generated("/presets/index.json", [text = index.dump()] { return text; }, "application/json");
}

/// /served.json: {"file": the served file's name}, for the page's title.
void serve_name(StaticServer& server, const std::string& file) {
  const std::string text = nlohmann::json{{"file", std::filesystem::path(file).filename().string()}}.dump();
  server.add_generated("/served.json", [text] { return text; }, "application/json");
}

}  // namespace

void add_view_command(CLI::App& app, Context& context) {
  auto o = std::make_shared<ViewOptions>();
  CLI::App* sub = app.add_subcommand(
      "view", "Serve on 127.0.0.1 the viewer page for a .glb (play and scrub the motion in a browser), or for a "
              "preset (.json) the designer page: edit the control polylines and see the P-hedron fold live, with "
              "the core running in the browser (WebAssembly); prints the address and serves until interrupted");
  sub->add_option("file", o->file, "An animated .glb written by `phedra generate`, or a preset .json to design")->required();
  sub->add_option("--port", o->port, "Port on 127.0.0.1 (0: any free port)")->capture_default_str();
  sub->add_option("--web", o->web, "The viewer's directory, web/ with its node_modules (default: web/ of the source "
                                   "tree this binary was built from)");
  sub->add_option("--presets", o->presets, "The presets the pages list, a directory of preset .json files (default: "
                                           "presets/ of the source tree this binary was built from)");
  sub->add_option("--requests", o->requests, "Stop after this many requests (0: serve until interrupted)");
  sub->callback([o, &context] {
    namespace fs = std::filesystem;
    const std::string ext = fs::path(o->file).extension().string();
    if (ext != ".glb" && ext != ".json") {
      throw InvalidInputError("file", "the viewer shows .glb files (write one with `phedra generate PRESET -o FILE.glb`) "
                                      "and the designer edits presets (.json)");
    }
    if (!fs::is_regular_file(o->file)) throw IOError(o->file + ": no such file");
    if (ext == ".json") {
      // The designer edits presets: validated first, with the errors of every other command.
      load(context, o->file);
      if (!fs::is_regular_file(fs::path(o->web) / "wasm" / "phedra.mjs")) {
        throw IOError(o->web + "/wasm/phedra.mjs is missing: run `bash scripts/build-wasm.sh` first");
      }
      if (!fs::is_directory(fs::path(o->web) / "node_modules" / "three")) {
        throw IOError(o->web + "/node_modules/three is missing: run `bash scripts/setup.sh` first");
      }
      StaticServer server(o->web, o->port);
      server.add_file("/preset.json", o->file);
      serve_name(server, o->file);
      serve_presets(server, o->presets);
      context.out << "designer for " << o->file << " at http://127.0.0.1:" << server.port() << "/designer.html"
                  << std::endl;
      server.serve(o->requests);
      return;
    }
    if (!fs::is_regular_file(fs::path(o->web) / "index.html")) {
      throw IOError(o->web + ": the viewer page (index.html) is not there; give --web DIR");
    }
    if (!fs::is_directory(fs::path(o->web) / "node_modules" / "three")) {
      throw IOError(o->web + "/node_modules/three is missing: run `bash scripts/setup.sh` first");
    }
    StaticServer server(o->web, o->port);
    server.add_file("/model.glb", o->file);
    serve_name(server, o->file);
    serve_presets(server, o->presets);
    context.out << "viewer for " << o->file << " at http://127.0.0.1:" << server.port() << "/" << std::endl;
    server.serve(o->requests);
  });
}

}  // namespace phedra::cli
