// SPDX-License-Identifier: Apache-2.0
// The scene readers: trace files (scene_trace.cpp) and Wavefront OBJ meshes with their
// MTL files (scene_obj.cpp), into the command stream of ref/scene.h.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "config/obj_placement.h"
#include "ref/scene.h"

namespace rastsim {

// Parse a trace file. Throws SceneError("file:line: ...") on any malformed input.
Scene load_trace(const std::string& path);
Scene parse_trace(const std::string& text, const std::string& name);

// Parse a Wavefront OBJ (with its mtllib files, looked up beside it) and place it.
Scene load_obj(const std::string& path, const ObjPlacement& placement);
Scene parse_obj(const std::string& text, const std::string& name, const ObjPlacement& placement,
                const std::string& base_dir);

// The command stream of a scene in batches: `consume` gets each batch of at least
// `batch` commands or of the commands of at least `batch` lines of a trace (the last may
// be shorter) in order, and may take them (the vector is cleared after). A trace is read
// chunk by chunk and parsed as it is consumed, so memory stays bounded whatever the
// file's size; a malformed line throws its SceneError (file:line) when the parser
// reaches it, after the batches before it were consumed. An OBJ mesh is read whole (its
// placement needs every vertex), then handed out in batches.
using CommandBatchFn = std::function<void(std::vector<Command>&)>;
void stream_trace(const std::string& path, size_t batch, const CommandBatchFn& consume);
void stream_scene(const std::string& path, const ObjPlacement& placement, size_t batch,
                  const CommandBatchFn& consume);

// stream_scene with the reader on a thread of its own, up to `batches_ahead` batches in
// front of `consume` (parsing a trace of small triangles costs about as much as drawing
// it in the reference model, and overlaps the drawing or the simulation). Memory stays
// bounded by those batches. As with stream_scene, a parse error reaches the caller after
// every batch before it was consumed; an exception from `consume` stops the reader and
// passes unchanged.
// render and simulate read kSceneBatchesAhead batches ahead.
inline constexpr size_t kSceneBatchesAhead = 2;
void stream_scene_ahead(const std::string& path, const ObjPlacement& placement, size_t batch_commands,
                        size_t batches_ahead, const CommandBatchFn& consume);

// The reader of stream_scene_ahead as an object, for a consumer that pulls: the thread
// starts parsing when it is constructed (so a simulation elaborates meanwhile), next()
// hands over the batches in order, and a parse error is thrown by the next() after the
// last batch before it. The destructor stops the reader and waits for it.
class SceneAhead {
 public:
  SceneAhead(const std::string& path, const ObjPlacement& placement, size_t batch_commands, size_t batches_ahead);
  ~SceneAhead();
  SceneAhead(const SceneAhead&) = delete;
  SceneAhead& operator=(const SceneAhead&) = delete;
  // The next batch into `batch` (true), or false at the end of the scene.
  bool next(std::vector<Command>& batch);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// What an OBJ scene reads but does not use (Scene::obj_ignored, statement -> count),
// read again from the file without placing it; nullopt for a trace. load_obj also
// prints these counts once per file on stderr ("bunny.obj: ignored: vn 34834, s 1").
// `l` and `p` are counted unless `camera` (scene.camera) is perspective, which draws them.
std::optional<StatementCounts> obj_ignored_counts(const std::string& path, ObjCamera camera = ObjCamera::Ortho);

// True when `path` names an OBJ mesh: the name, without any .gz / .zst, ends in .obj (any case).
bool is_obj_path(const std::string& path);

// By extension, after any .gz / .zst: .obj -> load_obj, anything else -> load_trace.
// Every loader reads plain, gzip and zstd files alike (scene_stream.h).
Scene load_scene(const std::string& path, const ObjPlacement& placement);

}  // namespace rastsim
