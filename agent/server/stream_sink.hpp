#pragma once

#include <google/protobuf/message.h>

namespace kapfix::agent {

// Where the agent's parts hand their stream messages: StreamPublisher on the link, a recorder
// in tests.
class StreamSink {
 public:
  virtual ~StreamSink() = default;
  // Thread-safe, never blocks on the network; false when the message was dropped.
  virtual bool Publish(const google::protobuf::Message& message) = 0;
};

}  // namespace kapfix::agent
