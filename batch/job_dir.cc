#include "batch/job_dir.h"

#include <sstream>

#include "common/atomic_file.h"
#include "common/error.h"

namespace brdfrig::batch {

namespace fs = std::filesystem;

JobDir::JobDir(const fs::path& dir) : root(fs::absolute(dir).lexically_normal()) {}

fs::path JobDir::result(int index) const { return results() / (std::to_string(index) + ".json"); }

std::vector<Submission> ReadSubmissions(const JobDir& dir) {
  std::vector<Submission> submissions;
  if (!fs::exists(dir.submissions())) return submissions;
  std::istringstream lines(ReadFileToString(dir.submissions()));
  std::string line;
  int number = 0;
  while (std::getline(lines, line)) {
    ++number;
    if (line.empty()) continue;
    std::istringstream words(line);
    Submission s;
    if (!(words >> s.job_id >> s.array)) {
      throw FileError(dir.submissions().string(), number, 1,
                      "expected \"<job id> <array spec>\", got \"" + line + "\"");
    }
    submissions.push_back(s);
  }
  return submissions;
}

void RecordSubmission(const JobDir& dir, const Submission& submission) {
  std::string text =
      fs::exists(dir.submissions()) ? ReadFileToString(dir.submissions()) : std::string();
  text += submission.job_id + " " + submission.array + "\n";
  WriteFileAtomically(dir.submissions(), text);
}

}  // namespace brdfrig::batch
