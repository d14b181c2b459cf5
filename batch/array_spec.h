// Slurm's job-array index lists ("0-9%4", "1,3,5-7", "[2-4]"): written for submissions and
// read back from submissions.txt and from squeue/sacct ids such as "123_[4-6%2]".
#pragma once

#include <string>
#include <vector>

namespace brdfrig::batch {

// "0-3,7" for {0,1,2,3,7}; with throttle > 0, "%throttle" appended (at most that many tasks of
// the array run at once). `indices` must be non-empty; they are sorted and deduplicated.
std::string ArraySpec(std::vector<int> indices, int throttle = 0);

// The indices of a spec, sorted, without the throttle; brackets are accepted ("[0-3%2]").
// Throws Error naming the spec when it is malformed.
std::vector<int> ExpandArraySpec(const std::string& spec);

}  // namespace brdfrig::batch
