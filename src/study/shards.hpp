#pragma once
// Shards of a plan live in core/shards.hpp (`process` campaigns shard too).
#include "core/shards.hpp"
