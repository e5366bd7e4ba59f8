// Copyright 2026 The colcon-wasm authors
//
// Licensed under the Apache License, Version 2.0 (the "License");
// you may not use this file except in compliance with the License.
// You may obtain a copy of the License at
//
//     http://www.apache.org/licenses/LICENSE-2.0
//
// Unless required by applicable law or agreed to in writing, software
// distributed under the License is distributed on an "AS IS" BASIS,
// WITHOUT WARRANTIES OR CONDITIONS OF ANY KIND, either express or implied.
// See the License for the specific language governing permissions and
// limitations under the License.

#include "rcutils/logging.h"
#include "rmw/error_handling.h"
#include "rmw/features.h"
#include "rmw/rmw.h"

#include "detail/identifier.hpp"

extern "C"
{

const char * rmw_get_implementation_identifier(void)
{
  return rmw_wasm_cpp::kIdentifier;
}

bool rmw_feature_supported(rmw_feature_t feature)
{
  switch (feature) {
    // The bus numbers every publication and every take.
    case RMW_FEATURE_MESSAGE_INFO_PUBLICATION_SEQUENCE_NUMBER:
    case RMW_FEATURE_MESSAGE_INFO_RECEPTION_SEQUENCE_NUMBER:
      return true;
    default:
      return false;
  }
}

rmw_ret_t rmw_set_log_severity(rmw_log_severity_t severity)
{
  switch (severity) {
    case RMW_LOG_SEVERITY_DEBUG:
    case RMW_LOG_SEVERITY_INFO:
    case RMW_LOG_SEVERITY_WARN:
    case RMW_LOG_SEVERITY_ERROR:
    case RMW_LOG_SEVERITY_FATAL:
      break;
    default:
      RMW_SET_ERROR_MSG_WITH_FORMAT_STRING("unknown log severity %d", static_cast<int>(severity));
      return RMW_RET_INVALID_ARGUMENT;
  }
  if (rcutils_logging_set_logger_level(
      rmw_wasm_cpp::kIdentifier, static_cast<int>(severity)) != RCUTILS_RET_OK)
  {
    RMW_SET_ERROR_MSG("cannot set the severity of the rmw_wasm_cpp logger");
    return RMW_RET_ERROR;
  }
  return RMW_RET_OK;
}

}  // extern "C"
