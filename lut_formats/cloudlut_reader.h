// cloudlut_reader.h — compatibility include for engines written against the single-header
// reader of cloudlut 0.1: it brings in the binary table reader (cloudlut_lut.h) and the
// manifest/JSON reader (cloudlut_manifest.h). New code includes the one it needs.
// Since the split a Lut keeps only its decoded values (no `payload`).
#ifndef CLOUDLUT_READER_H
#define CLOUDLUT_READER_H

#include "cloudlut_lut.h"
#include "cloudlut_manifest.h"

#endif  // CLOUDLUT_READER_H
