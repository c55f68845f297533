// Implements batch/Summary.h; what it computes, its rules and its contract are documented there.
#include "batch/Summary.h"

#include <algorithm>
#include <cstdio>

namespace jawmesh {
namespace {
std::string format(const char* fmt, double value) {
    char text[64];
    std::snprintf(text, sizeof text, fmt, value);
    return text;
}

std::string csvField(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

std::string megabytes(std::uint64_t bytes) { return format("%.0f", static_cast<double>(bytes) / 1e6); }

std::string pad(const std::string& s, std::size_t width) { return s.size() >= width ? s : s + std::string(width - s.size(), ' '); }
std::string padLeft(const std::string& s, std::size_t width) {
    return s.size() >= width ? s : std::string(width - s.size(), ' ') + s;
}
}  // namespace

StatusCounts countStatuses(const BatchManifest& m) {
    StatusCounts c;
    for (const TaskRecord& r : m.tasks) {
        if (r.status == TaskStatus::Ok) ++c.ok;
        if (r.status == TaskStatus::Ok && r.reused) ++c.reused;
        if (r.status == TaskStatus::Failed) ++c.failed;
        if (r.status == TaskStatus::Pending) ++c.pending;
    }
    return c;
}

std::string summaryTable(const BatchManifest& m) {
    std::size_t caseWidth = 4;
    for (const TaskRecord& r : m.tasks) caseWidth = std::max(caseWidth, r.task.caseName.size());
    std::string out = pad("case", caseWidth) + "  jaw       status   seconds  peak MB  note\n";
    for (const TaskRecord& r : m.tasks) {
        const bool ran = r.status != TaskStatus::Pending;
        const std::string note = r.status == TaskStatus::Failed ? r.error : r.reused ? "reused (outputs valid)" : "";
        out += pad(r.task.caseName, caseWidth) + "  " + pad(r.task.jaw.empty() ? "-" : r.task.jaw, 8) + "  " +
               pad(statusName(r.status), 7) + "  " + padLeft(ran ? format("%.1f", r.seconds) : "-", 7) + "  " +
               padLeft(ran && r.peakMemoryBytes ? megabytes(r.peakMemoryBytes) : "-", 7) + "  " + note + "\n";
    }
    const StatusCounts c = countStatuses(m);
    out += std::to_string(c.ok) + " ok (" + std::to_string(c.reused) + " reused), " + std::to_string(c.failed) +
           " failed, " + std::to_string(c.pending) + " pending\n";
    return out;
}

std::string summaryCsv(const BatchManifest& m) {
    std::string out = "case,jaw,status,reused,seconds,peak_memory_mb,estimated_memory_mb,error,log\n";
    for (const TaskRecord& r : m.tasks)
        out += csvField(r.task.caseName) + "," + csvField(r.task.jaw) + "," + statusName(r.status) + "," +
               (r.reused ? "true" : "false") + "," + format("%.3f", r.seconds) + "," + megabytes(r.peakMemoryBytes) +
               "," + megabytes(r.estimatedMemoryBytes) + "," + csvField(r.error) + "," + csvField(r.log) + "\n";
    return out;
}

}  // namespace jawmesh
