// Every message type of kapfix.v1 survives the codec with every field set, and the schema
// keeps its rules (header at field 1, UNSPECIFIED = 0, retired fields reserved).
#include <google/protobuf/descriptor.h>
#include <google/protobuf/util/message_differencer.h>
#include <gtest/gtest.h>

#include <memory>
#include <set>
#include <string>
#include <vector>

#include "kapfix/v1/command.pb.h"
#include "kapfix/v1/envelope_codec.hpp"
#include "kapfix/v1/telemetry.pb.h"
#include "link/envelope.hpp"
#include "link/topic_table.hpp"

namespace kapfix::v1 {
namespace {

using google::protobuf::Descriptor;
using google::protobuf::EnumDescriptor;
using google::protobuf::FieldDescriptor;
using google::protobuf::FileDescriptor;
using google::protobuf::Message;
using google::protobuf::Reflection;
using google::protobuf::util::MessageDifferencer;
using kapfix::link::DecodeEnvelope;
using kapfix::link::Encode;
using kapfix::link::Envelope;
using kapfix::link::NewMessageForTopic;
using kapfix::link::Topics;

void FillEveryField(Message* message);

// Sets (or, for a repeated field, appends) a value that is never the field's default.
void SetValue(Message* message, const FieldDescriptor* field, int k = 0) {
  const Reflection* r = message->GetReflection();
  const bool rep = field->is_repeated();
  switch (field->cpp_type()) {
    case FieldDescriptor::CPPTYPE_INT32:
      rep ? r->AddInt32(message, field, -7 - k) : r->SetInt32(message, field, -7);
      break;
    case FieldDescriptor::CPPTYPE_INT64:
      rep ? r->AddInt64(message, field, -1'700'000'000'000'000 - k)
          : r->SetInt64(message, field, -1'700'000'000'000'000);
      break;
    case FieldDescriptor::CPPTYPE_UINT32:
      rep ? r->AddUInt32(message, field, 7U + static_cast<unsigned>(k))
          : r->SetUInt32(message, field, 7U);
      break;
    case FieldDescriptor::CPPTYPE_UINT64:
      rep ? r->AddUInt64(message, field, 1ULL << 40U) : r->SetUInt64(message, field, 1ULL << 40U);
      break;
    case FieldDescriptor::CPPTYPE_DOUBLE:
      rep ? r->AddDouble(message, field, 2.5 + k) : r->SetDouble(message, field, 2.5);
      break;
    case FieldDescriptor::CPPTYPE_FLOAT:
      rep ? r->AddFloat(message, field, -1.25F - static_cast<float>(k))
          : r->SetFloat(message, field, -1.25F);
      break;
    case FieldDescriptor::CPPTYPE_BOOL:
      rep ? r->AddBool(message, field, true) : r->SetBool(message, field, true);
      break;
    case FieldDescriptor::CPPTYPE_ENUM: {
      const EnumDescriptor* type = field->enum_type();
      const int value = type->value(type->value_count() - 1)->number();
      rep ? r->AddEnumValue(message, field, value) : r->SetEnumValue(message, field, value);
      break;
    }
    case FieldDescriptor::CPPTYPE_STRING: {
      const std::string value = field->type() == FieldDescriptor::TYPE_BYTES
                                    ? std::string("\0\xff\xd8 jpeg", 8)
                                    : "text of " + field->name() + " µ";
      rep ? r->AddString(message, field, value) : r->SetString(message, field, value);
      break;
    }
    case FieldDescriptor::CPPTYPE_MESSAGE:
      FillEveryField(rep ? r->AddMessage(message, field) : r->MutableMessage(message, field));
      break;
  }
}

// Fields a fill leaves alone: every oneof case but the first.
bool SkippedByFill(const FieldDescriptor* field) {
  return field->real_containing_oneof() != nullptr && field->index_in_oneof() != 0;
}

void FillEveryField(Message* message) {
  const Descriptor* type = message->GetDescriptor();
  for (int i = 0; i < type->field_count(); ++i) {
    const FieldDescriptor* field = type->field(i);
    if (SkippedByFill(field)) continue;
    SetValue(message, field, 0);
    if (field->is_repeated()) SetValue(message, field, 1);
  }
}

// Names of fields (recursively) that hold their default: a fill that missed something.
void CollectUnset(const Message& message, const std::string& prefix,
                  std::vector<std::string>* unset) {
  const Descriptor* type = message.GetDescriptor();
  const Reflection* r = message.GetReflection();
  for (int i = 0; i < type->field_count(); ++i) {
    const FieldDescriptor* field = type->field(i);
    if (SkippedByFill(field)) continue;
    const std::string name = prefix + field->name();
    if (field->is_repeated() ? r->FieldSize(message, field) == 0 : !r->HasField(message, field)) {
      unset->push_back(name);
    } else if (field->cpp_type() == FieldDescriptor::CPPTYPE_MESSAGE && !field->is_repeated()) {
      CollectUnset(r->GetMessage(message, field), name + ".", unset);
    }
  }
}

Header* MutableHeader(Message* message) {
  const FieldDescriptor* field = message->GetDescriptor()->FindFieldByNumber(1);
  return google::protobuf::DynamicCastToGenerated<Header>(
      message->GetReflection()->MutableMessage(message, field));
}

// Encode, then DecodeEnvelope into a fresh message of the same type.
std::unique_ptr<Message> RoundTrip(const Message& sent) {
  const Envelope envelope = Encode(sent);
  std::unique_ptr<Message> received(sent.New());
  std::string error;
  EXPECT_TRUE(
      DecodeEnvelope(envelope.topic, envelope.payload, received.get(), kMaxMessageBytes, &error))
      << error;
  return received;
}

std::string ParamName(const ::testing::TestParamInfo<std::string>& param) { return param.param; }

class ProtoRoundTripTest : public ::testing::TestWithParam<std::string> {};

TEST_P(ProtoRoundTripTest, EveryFieldSurvivesEncodeAndDecode) {
  const std::unique_ptr<Message> sent = NewMessageForTopic(GetParam());
  ASSERT_NE(sent, nullptr);
  FillEveryField(sent.get());
  Stamp(MutableHeader(sent.get()), "kite-1", 42, 0x5eed);  // an agent: with a boot id
  std::vector<std::string> unset;
  CollectUnset(*sent, "", &unset);
  ASSERT_TRUE(unset.empty()) << "fill missed " << ::testing::PrintToString(unset);

  const std::unique_ptr<Message> received = RoundTrip(*sent);
  std::string difference;
  MessageDifferencer differencer;
  differencer.ReportDifferencesToString(&difference);
  EXPECT_TRUE(differencer.Compare(*sent, *received)) << difference;
}

INSTANTIATE_TEST_SUITE_P(EveryTopic, ProtoRoundTripTest, ::testing::ValuesIn(Topics()), ParamName);

// Command's oneof holds one setting at a time: each case on its own.
class CommandRoundTripTest : public ::testing::TestWithParam<std::string> {};

TEST_P(CommandRoundTripTest, OneofCaseSurvivesEncodeAndDecode) {
  Command sent;
  Stamp(sent.mutable_header(), "kite-1", 7);
  const FieldDescriptor* field = Command::descriptor()->FindFieldByName(GetParam());
  ASSERT_NE(field, nullptr);
  SetValue(&sent, field);

  const std::unique_ptr<Message> received = RoundTrip(sent);
  const auto* command = google::protobuf::DynamicCastToGenerated<Command>(received.get());
  ASSERT_NE(command, nullptr);
  EXPECT_EQ(static_cast<int>(command->command_case()), field->number());
  EXPECT_TRUE(MessageDifferencer::Equals(sent, *command));
}

std::vector<std::string> CommandCases() {
  std::vector<std::string> names;
  const auto* oneof = Command::descriptor()->FindOneofByName("command");
  names.reserve(static_cast<std::size_t>(oneof->field_count()));
  for (int i = 0; i < oneof->field_count(); ++i) names.push_back(oneof->field(i)->name());
  return names;
}

INSTANTIATE_TEST_SUITE_P(EveryCase, CommandRoundTripTest, ::testing::ValuesIn(CommandCases()),
                         ParamName);

TEST(ProtoSchemaTest, CommandOneofCoversEverySettingAndMode) {
  const std::set<std::string> expected = {"set_mode",   "set_gains", "set_search", "select_slice",
                                          "set_camera", "set_lens",  "take_photo", "request_state",
                                          "set_video",  "set_photo"};
  const std::vector<std::string> cases = CommandCases();
  EXPECT_EQ(std::set<std::string>(cases.begin(), cases.end()), expected);
}

TEST(ProtoSchemaTest, ModeEnumHasEveryAgentMode) {
  std::set<std::string> names;
  for (int i = 0; i < Mode_descriptor()->value_count(); ++i) {
    names.insert(Mode_descriptor()->value(i)->name());
  }
  EXPECT_EQ(names, (std::set<std::string>{"MODE_UNSPECIFIED", "MODE_IDLE", "MODE_CALIBRATE",
                                          "MODE_PSS", "MODE_SSP", "MODE_FIXATE", "MODE_FOLLOW",
                                          "MODE_RECORD_FREE_SWING"}));
}

TEST(ProtoSchemaTest, EveryTopicMessageCarriesHeaderAsFieldOne) {
  for (const std::string& topic : Topics()) {
    const Descriptor* type = NewMessageForTopic(topic)->GetDescriptor();
    const FieldDescriptor* field = type->FindFieldByNumber(1);
    ASSERT_NE(field, nullptr) << type->full_name();
    EXPECT_EQ(field->name(), "header") << type->full_name();
    EXPECT_EQ(field->message_type(), Header::descriptor()) << type->full_name();
  }
}

void CollectFiles(const FileDescriptor* file, std::set<const FileDescriptor*>* files) {
  if (file->package() != "kapfix.v1" || !files->insert(file).second) return;
  for (int i = 0; i < file->dependency_count(); ++i) CollectFiles(file->dependency(i), files);
}

void CollectEnums(const Descriptor* type, std::vector<const EnumDescriptor*>* enums) {
  for (int i = 0; i < type->enum_type_count(); ++i) enums->push_back(type->enum_type(i));
  for (int i = 0; i < type->nested_type_count(); ++i) CollectEnums(type->nested_type(i), enums);
}

TEST(ProtoSchemaTest, EveryEnumStartsWithUnspecifiedZero) {
  std::set<const FileDescriptor*> files;
  for (const std::string& topic : Topics()) {
    CollectFiles(NewMessageForTopic(topic)->GetDescriptor()->file(), &files);
  }
  std::vector<const EnumDescriptor*> enums;
  for (const FileDescriptor* file : files) {
    for (int i = 0; i < file->enum_type_count(); ++i) enums.push_back(file->enum_type(i));
    for (int i = 0; i < file->message_type_count(); ++i) {
      CollectEnums(file->message_type(i), &enums);
    }
  }
  ASSERT_GE(enums.size(), 8U);  // Mode, Axis, Sampling, Channel, SliceScoreKind, …
  for (const EnumDescriptor* e : enums) {
    const auto* zero = e->FindValueByNumber(0);
    ASSERT_NE(zero, nullptr) << e->full_name();
    EXPECT_TRUE(zero->name().ends_with("_UNSPECIFIED")) << e->full_name();
    EXPECT_EQ(e->value(0), zero) << e->full_name() << ": the zero value comes first";
  }
}

TEST(ProtoSchemaTest, TelemetryKeepsItsRetiredFieldReserved) {
  const Descriptor* type = Telemetry::descriptor();
  EXPECT_TRUE(type->IsReservedNumber(9));
  EXPECT_TRUE(type->IsReservedName("displacement_px"));
  EXPECT_EQ(type->FindFieldByNumber(9), nullptr);
}

}  // namespace
}  // namespace kapfix::v1
