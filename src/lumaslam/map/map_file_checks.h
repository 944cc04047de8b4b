#pragma once
// What a decoded map file must satisfy before anything is built from it (map_file.cpp): the
// fingerprint's camera and ORB settings are usable, every array agrees in length, every id is
// known, and every number is in range (keypoints inside the image and the pyramid, finite
// poses, positions and depths), so that a file that passed its checksum but was written wrongly
// is an Error naming the file and the problem, never a map that fails later in tracking.
#include <string>

#include "lumaslam/map/map_file.h"
#include "lumaslam/map/map_file_records.h"

namespace lumaslam::map {

// Throws Error "NAME: ..." for the first problem found.
void checkMapRecord(const MapFingerprint& fingerprint, const MapRecord& record,
                    const std::string& name);

}  // namespace lumaslam::map
