// A dataset is a folder of case folders in the Open-Full-Jaw dataset layout:
//   <dataset>/<case>/input/<jaw>/...      e.g. <dataset>/Patient_26/input/mandible/bone/mandible.stl
// A batch runs one task per (case, jaw). A case folder that is not a valid case (io/Case.h) is one
// failed task carrying discoverCase's message, so a broken case is reported, never skipped silently.
#pragma once

#include <string>
#include <vector>

namespace jawmesh {

/// One unit of batch work: a jaw of a case, or a case that could not even be listed.
struct DatasetTask {
    std::string caseName;        ///< the case folder's name (also its output folder's name)
    std::string caseDir;         ///< absolute path of the case folder
    std::string jaw;             ///< "mandible" | "maxilla"; empty when the case could not be listed
    std::string discoveryError;  ///< discoverCase's message when jaw is empty
};

/// Every (case, jaw) of a dataset, cases in name order, mandible before maxilla. Every sub-folder
/// whose name does not start with '.' is a case, except excludeDir (a batch's output folder may
/// live inside its dataset); files beside the cases are ignored.
/// Throws Error when the dataset folder does not exist, is itself a case (has input/), or holds
/// no case folder. Cost: a few directory listings per case (no surface is read).
std::vector<DatasetTask> discoverDataset(const std::string& datasetDir, const std::string& excludeDir = "");

/// "<case>/<jaw>" (or "<case>" for a case that could not be listed): the task's name in tables,
/// logs and messages.
std::string taskName(const DatasetTask& task);

}  // namespace jawmesh
