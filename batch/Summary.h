// The batch summary: a fixed-width table for the terminal and the same rows as CSV.
#pragma once

#include "batch/Manifest.h"

#include <string>

namespace jawmesh {

/// One line per task (case, jaw, status, seconds, peak MB, note: "reused" or the error) and a
/// totals line ("6 ok (6 reused), 1 failed, 0 pending").
std::string summaryTable(const BatchManifest& manifest);

/// Header case,jaw,status,reused,seconds,peak_memory_mb,estimated_memory_mb,error,log; fields quoted
/// per RFC 4180 where needed.
std::string summaryCsv(const BatchManifest& manifest);

struct StatusCounts {
    int ok = 0, reused = 0, failed = 0, pending = 0;
};
StatusCounts countStatuses(const BatchManifest& manifest);

}  // namespace jawmesh
