// What a batch has to do, decided from the dataset and from what is already on disk: a task whose
// output folder carries a valid completion stamp for the same options hash is done (reused);
// everything else (never run, failed, partial, stale options, damaged file) is to be (re)done.
#pragma once

#include "batch/Manifest.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace jawmesh {

/// Files every complete output folder of a jaw must list in its stamp (run.json and the volume
/// meshes), relative to <out>/<case>/<jaw>.
std::vector<std::string> requiredOutputs(const std::string& jaw);

/// The manifest for a batch of datasetDir into outDir: one record per task (batch/Dataset.h), Ok and
/// reused when its outputs validate (batch/OutputStamp.h), Failed for a case that cannot be listed,
/// else Pending with a memory estimate (batch/MemoryEstimate.h; 0 when the surfaces cannot be read:
/// the task itself will report why). options is runOptionsToJson of the run options (its voxel_mm
/// sets the estimate). Throws Error for a missing or empty dataset folder.
/// Cost: checksums every existing output once; reads the surfaces of every pending jaw once.
BatchManifest planBatch(const std::string& datasetDir, const std::string& outDir, const nlohmann::json& options,
                        const std::string& optionsHash, const std::string& jawmeshVersion);

/// A task's state as found on disk, for --status and after a local task ends: Ok when its outputs
/// validate; else the task's own result record when it is for optionsHash (Failed with its error;
/// an Ok record whose outputs no longer validate is Failed with the reason); else Pending, with
/// `missing` as error (e.g. "no result yet"). Records of cases that could not be listed are kept.
TaskRecord collectTaskStatus(const TaskRecord& planned, const std::string& outDir, const std::string& optionsHash,
                             const std::string& missing);

}  // namespace jawmesh
