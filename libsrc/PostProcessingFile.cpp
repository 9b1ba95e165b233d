#include "FunctionObject.hpp"

#include "CaseWriter.hpp"

#include <cerrno>
#include <iomanip>
#include <stdexcept>

namespace spindrift {

PostProcessingFile::PostProcessingFile(const std::filesystem::path& caseDir, const std::string& name,
                                       double startTime, const std::vector<PostProcessingColumn>& columns,
                                       const std::string& fileName) {
    for (const auto& c : columns)
        if (c.unit.empty()) throw std::logic_error("postProcessing/" + name + ": column '" + c.name + "' has no unit");
    const auto dir = caseDir / "postProcessing" / name / CaseWriter::timeName(startTime);
    std::filesystem::create_directories(dir);
    path_ = dir / ((fileName.empty() ? name : fileName) + ".dat");
    errno = 0;
    out_.open(path_, std::ios::trunc);
    if (!out_) throw std::runtime_error(describeWriteFailure(path_.string(), errno));
    out_ << "# Time";
    for (const auto& c : columns) out_ << '\t' << c.name;
    out_ << "\n# [s]";
    for (const auto& c : columns) out_ << "\t[" << c.unit << ']';
    out_ << '\n' << std::flush;
    if (!out_) throw std::runtime_error(describeWriteFailure(path_.string(), errno));
}

void PostProcessingFile::writeRow(double time, const std::vector<double>& values) {
    errno = 0;
    out_ << std::setprecision(10) << time;
    for (double v : values) out_ << '\t' << v;
    out_ << '\n' << std::flush;
    // a full disk: stop, rather than run on losing the rows
    if (out_.is_open() && !out_) throw std::runtime_error(describeWriteFailure(path_.string(), errno));
}

} // namespace spindrift
