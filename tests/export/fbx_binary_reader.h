// A reader of binary FBX 7.4 for the tests, written from the format's public description alone
// (Blender's 2013 write-up): the records back as FbxRecords, every end offset and length checked
// against where the record's parts really end, deflated arrays inflated (their count given in
// `deflated_arrays`), and the header and footer checked byte for byte. Fails (an error naming the
// offset) on anything else.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/export/fbx_binary.h"

namespace mg::test {

Result<std::vector<FbxRecord>> read_fbx_binary(std::string_view bytes, int* deflated_arrays = nullptr);

// The first record of that name among `records`, or null.
const FbxRecord* find_record(const std::vector<FbxRecord>& records, const std::string& name);

}  // namespace mg::test
