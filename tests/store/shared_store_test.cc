#include "store/shared_store.h"

#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <thread>

#include "gtest/gtest.h"
#include "store/entry_file.h"

namespace aperture {
namespace {

namespace fs = std::filesystem;

std::vector<std::byte> Bytes(std::string_view text) {
  std::vector<std::byte> bytes(text.size());
  std::memcpy(bytes.data(), text.data(), text.size());
  return bytes;
}

std::string Text(std::span<const std::byte> bytes) {
  return std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

class SharedStoreTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    directory_ = fs::path("/dev/shm") / (std::string("aperture-store-test-") + info->name() + "-" +
                                         std::to_string(getpid()));
    fs::remove_all(directory_);
  }
  void TearDown() override { fs::remove_all(directory_); }

  std::shared_ptr<SharedStore> OpenStore() {
    auto store = SharedStore::Open(directory_.string());
    EXPECT_TRUE(store.ok()) << store.status();
    return *store;
  }
  fs::path EntryFile(const std::string& key) { return directory_ / (key + ".entry"); }

  fs::path directory_;
};

TEST_F(SharedStoreTest, PublishedEntryIsReadBackByAnotherStoreOnTheDirectory) {
  auto writer = OpenStore();
  auto put = writer->Put("blob-1", EntryKind::kBlob, Bytes("hello, shared memory"));
  ASSERT_TRUE(put.ok()) << put.status();
  EXPECT_EQ(Text((*put)->payload()), "hello, shared memory");
  EXPECT_EQ(reinterpret_cast<uintptr_t>((*put)->payload().data()) % kPayloadAlignment, 0u);

  auto reader = OpenStore();  // as a second process would
  auto attached = reader->Attach("blob-1", EntryKind::kBlob);
  ASSERT_TRUE(attached.ok()) << attached.status();
  EXPECT_EQ(Text((*attached)->payload()), "hello, shared memory");
  EXPECT_EQ(reader->counters().attached, 1u);
  EXPECT_EQ(reader->counters().built, 0u);
  EXPECT_TRUE(reader->Has("blob-1", EntryKind::kBlob));
  EXPECT_FALSE(reader->Has("blob-2", EntryKind::kBlob));
}

// The store kept under a budget, least recently used entries first; an entry
// still mapped stays readable to whoever holds it.
TEST_F(SharedStoreTest, TrimEvictsTheLeastRecentlyUsedAndMappedEntriesStayValid) {
  auto store = OpenStore();
  const std::string payload(100000, 'x');
  std::shared_ptr<const StoreEntry> held;
  for (const std::string key : {"a", "b", "c"}) {
    auto put = store->Put(key, EntryKind::kBlob, Bytes(payload + key));
    ASSERT_TRUE(put.ok()) << put.status();
    if (key == "a") held = *put;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_TRUE(store->Attach("a", EntryKind::kBlob).ok());  // "a" used last: "b" is the oldest
  const uint64_t total = store->TotalBytes();
  EXPECT_GT(total, 3 * payload.size());

  const StoreTrim trim = store->Trim(total - 1);
  EXPECT_EQ(trim.entries_evicted, 1u);
  EXPECT_EQ(trim.bytes_before, total);
  EXPECT_LT(trim.bytes_after, total);
  EXPECT_EQ(store->TotalBytes(), trim.bytes_after);
  EXPECT_FALSE(store->Has("b", EntryKind::kBlob));
  EXPECT_TRUE(store->Has("a", EntryKind::kBlob));
  EXPECT_TRUE(store->Has("c", EntryKind::kBlob));

  EXPECT_EQ(store->Trim(0).entries_evicted, 2u);
  EXPECT_EQ(store->TotalBytes(), 0u);
  EXPECT_EQ(Text(held->payload()), payload + "a");  // still mapped, still whole
  EXPECT_EQ(store->counters().evicted, 3u);
  EXPECT_FALSE(store->Has("a", EntryKind::kBlob));
}

TEST_F(SharedStoreTest, WithABudgetRoomIsMadeBeforeAnEntryIsWritten) {
  auto store = OpenStore();
  const std::string payload(100000, 'y');
  store->SetBudget(250000);  // two entries and their headers, not three
  for (const std::string key : {"a", "b", "c"}) {
    ASSERT_TRUE(store->Put(key, EntryKind::kBlob, Bytes(payload + key)).ok());
    EXPECT_LE(store->TotalBytes(), 250000u);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_FALSE(store->Has("a", EntryKind::kBlob));
  EXPECT_TRUE(store->Has("c", EntryKind::kBlob));
  auto big = store->Put("big", EntryKind::kBlob, Bytes(std::string(300000, 'z')));
  ASSERT_FALSE(big.ok());
  EXPECT_TRUE(absl::IsResourceExhausted(big.status())) << big.status();
}

TEST_F(SharedStoreTest, AnEntryKnownTooLargeForTheBudgetIsRefusedBeforeItIsBuilt) {
  auto store = OpenStore();
  store->SetBudget(1 << 20, "--max-store-mb");
  int builds = 0;
  auto builder = [&]() -> absl::StatusOr<std::vector<std::byte>> {
    ++builds;
    return Bytes("never this");
  };
  auto refused = store->GetOrBuild("table-big", EntryKind::kSummedAreaTable, builder, nullptr,
                                   uint64_t{3} << 30);
  ASSERT_FALSE(refused.ok());
  EXPECT_TRUE(absl::IsResourceExhausted(refused.status())) << refused.status();
  EXPECT_NE(refused.status().message().find("3072 MiB"), std::string::npos) << refused.status();
  EXPECT_NE(refused.status().message().find("budget of 1 MiB (--max-store-mb)"), std::string::npos)
      << refused.status();
  EXPECT_EQ(builds, 0);
  EXPECT_EQ(store->TotalBytes(), 0u);  // not even a temporary file
  // One that fits is built as before.
  auto built = store->GetOrBuild("table-small", EntryKind::kSummedAreaTable, builder, nullptr, 10);
  ASSERT_TRUE(built.ok()) << built.status();
  EXPECT_EQ(builds, 1);
}

TEST_F(SharedStoreTest, MissingKeyIsNotFoundAndBadKeysAreRefused) {
  auto store = OpenStore();
  EXPECT_TRUE(absl::IsNotFound(store->Attach("nothing", EntryKind::kBlob).status()));
  for (const char* key : {"", ".hidden", "UPPER", "a/b", "../up"})
    EXPECT_TRUE(absl::IsInvalidArgument(store->Attach(key, EntryKind::kBlob).status())) << key;
  EXPECT_FALSE(SharedStore::IsValidKey(std::string(kMaxKeyLength + 1, 'a')));
  EXPECT_TRUE(SharedStore::IsValidKey("table-0123abcd.v1_x"));
}

TEST_F(SharedStoreTest, AnEntryOfAnotherKindIsRefused) {
  auto store = OpenStore();
  ASSERT_TRUE(store->Put("k", EntryKind::kBlob, Bytes("x")).ok());
  auto other = OpenStore();
  auto status = other->Attach("k", EntryKind::kPrefilteredTable).status();
  EXPECT_TRUE(absl::IsFailedPrecondition(status)) << status;
  EXPECT_NE(status.message().find("blob"), std::string::npos) << status;
}

TEST_F(SharedStoreTest, GetOrBuildBuildsOnceThenEveryStoreAttaches) {
  int builds = 0;
  auto builder = [&]() -> absl::StatusOr<std::vector<std::byte>> {
    ++builds;
    return Bytes("built payload");
  };
  auto first = OpenStore()->GetOrBuild("table-a", EntryKind::kPrefilteredTable, builder);
  ASSERT_TRUE(first.ok()) << first.status();
  auto second_store = OpenStore();
  auto second = second_store->GetOrBuild("table-a", EntryKind::kPrefilteredTable, builder);
  ASSERT_TRUE(second.ok()) << second.status();
  EXPECT_EQ(builds, 1);
  EXPECT_EQ(Text((*second)->payload()), "built payload");
  EXPECT_EQ(second_store->counters().attached, 1u);
  EXPECT_EQ(second_store->counters().built, 0u);
}

TEST_F(SharedStoreTest, ConcurrentBuildersOfOneKeyBuildItOnce) {
  std::atomic<int> builds{0};
  auto builder = [&]() -> absl::StatusOr<std::vector<std::byte>> {
    builds.fetch_add(1);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    return Bytes("slow payload");
  };
  std::vector<std::thread> threads;
  std::atomic<int> ok{0};
  for (int i = 0; i < 4; ++i)
    threads.emplace_back([&] {
      auto store = SharedStore::Open(directory_.string());  // each its own "process"
      if (!store.ok()) return;
      auto entry = (*store)->GetOrBuild("shared", EntryKind::kBlob, builder);
      if (entry.ok() && Text((*entry)->payload()) == "slow payload") ok.fetch_add(1);
    });
  for (auto& t : threads) t.join();
  EXPECT_EQ(ok.load(), 4);
  EXPECT_EQ(builds.load(), 1);
}

TEST_F(SharedStoreTest, ACorruptEntryIsDetectedNeverUsedAndRebuilt) {
  ASSERT_TRUE(OpenStore()->Put("blob", EntryKind::kBlob, Bytes("original bytes")).ok());
  {
    std::fstream file(EntryFile("blob"), std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(-3, std::ios::end);
    file.put('X');
  }
  auto store = OpenStore();
  auto status = store->Attach("blob", EntryKind::kBlob).status();
  EXPECT_TRUE(absl::IsDataLoss(status)) << status;
  EXPECT_NE(status.message().find("checksum"), std::string::npos) << status;

  int builds = 0;
  auto rebuilt = store->GetOrBuild("blob", EntryKind::kBlob, [&] {
    ++builds;
    return absl::StatusOr<std::vector<std::byte>>(Bytes("original bytes"));
  });
  ASSERT_TRUE(rebuilt.ok()) << rebuilt.status();
  EXPECT_EQ(builds, 1);
  EXPECT_EQ(Text((*rebuilt)->payload()), "original bytes");
  EXPECT_EQ(store->counters().rejected, 1u);
  EXPECT_TRUE(OpenStore()->Attach("blob", EntryKind::kBlob).ok());
}

TEST_F(SharedStoreTest, AnEntryTheReaderRefusesIsRebuiltOnceAndTheNewOneKept) {
  // An older build wrote the key with another layout: whole and checksummed, but its reader's
  // own check (the validator) refuses it.
  ASSERT_TRUE(OpenStore()->Put("table-x", EntryKind::kPrefilteredTable, Bytes("layout 1")).ok());
  auto layout_2 = [](std::span<const std::byte> payload) {
    return Text(payload) == "layout 2" ? absl::OkStatus()
                                       : absl::InvalidArgumentError("not layout 2");
  };
  int builds = 0;
  auto builder = [&] {
    ++builds;
    return absl::StatusOr<std::vector<std::byte>>(Bytes("layout 2"));
  };
  auto store = OpenStore();
  ASSERT_TRUE(store->Attach("table-x", EntryKind::kPrefilteredTable).ok());  // mapped first
  auto rebuilt = store->GetOrBuild("table-x", EntryKind::kPrefilteredTable, builder, layout_2);
  ASSERT_TRUE(rebuilt.ok()) << rebuilt.status();
  EXPECT_EQ(Text((*rebuilt)->payload()), "layout 2");
  EXPECT_EQ(builds, 1);
  EXPECT_EQ(store->counters().rejected, 1u);
  // Another process attaches the new entry without building.
  auto other = OpenStore();
  auto again = other->GetOrBuild("table-x", EntryKind::kPrefilteredTable, builder, layout_2);
  ASSERT_TRUE(again.ok()) << again.status();
  EXPECT_EQ(Text((*again)->payload()), "layout 2");
  EXPECT_EQ(builds, 1);
  EXPECT_EQ(other->counters().rejected, 0u);
  // Without a validator the store alone decides: the same entry is used as it is.
  EXPECT_EQ(
      Text((*OpenStore()->GetOrBuild("table-x", EntryKind::kPrefilteredTable, builder))->payload()),
      "layout 2");
}

TEST_F(SharedStoreTest, ATruncatedEntryIsDetected) {
  ASSERT_TRUE(OpenStore()->Put("blob", EntryKind::kBlob, Bytes(std::string(1000, 'z'))).ok());
  fs::resize_file(EntryFile("blob"), fs::file_size(EntryFile("blob")) - 10);
  auto status = OpenStore()->Attach("blob", EntryKind::kBlob).status();
  EXPECT_TRUE(absl::IsDataLoss(status)) << status;
}

TEST_F(SharedStoreTest, AnEntryNotMarkedCompleteIsNeverUsed) {
  // A writer that stops before publishing (as a crash would) leaves a file without the mark;
  // even under the final name it is refused.
  ASSERT_TRUE(OpenStore().get());
  {
    auto writer =
        EntryWriter::Begin((directory_ / "half.entry.tmp.1").string(), "half", EntryKind::kBlob);
    ASSERT_TRUE(writer.ok());
    fs::copy_file(directory_ / "half.entry.tmp.1", EntryFile("half"));
  }
  auto status = OpenStore()->Attach("half", EntryKind::kBlob).status();
  EXPECT_TRUE(absl::IsDataLoss(status)) << status;
  EXPECT_NE(status.message().find("half written"), std::string::npos) << status;
}

TEST_F(SharedStoreTest, ABuilderKilledMidBuildLeavesOnlyATemporaryThatIsSweptAndRebuilt) {
  ASSERT_TRUE(OpenStore().get());
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    auto store = SharedStore::Open(directory_.string());
    if (store.ok())
      (void)(*store)->GetOrBuild("slow", EntryKind::kBlob, [] {
        sleep(30);  // killed long before this returns
        return absl::StatusOr<std::vector<std::byte>>(std::vector<std::byte>{});
      });
    _exit(0);
  }
  const fs::path temporary = directory_ / ("slow.entry.tmp." + std::to_string(child));
  for (int i = 0; i < 500 && !fs::exists(temporary); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_TRUE(fs::exists(temporary));
  kill(child, SIGKILL);
  waitpid(child, nullptr, 0);

  EXPECT_FALSE(fs::exists(EntryFile("slow")));
  auto store = OpenStore();  // a restart: sweeps what the dead builder left
  EXPECT_FALSE(fs::exists(temporary));
  EXPECT_TRUE(absl::IsNotFound(store->Attach("slow", EntryKind::kBlob).status()));
  auto built = store->GetOrBuild("slow", EntryKind::kBlob, [] {
    return absl::StatusOr<std::vector<std::byte>>(Bytes("now complete"));
  });
  ASSERT_TRUE(built.ok()) << built.status();
  EXPECT_EQ(store->counters().built, 1u);
}

TEST_F(SharedStoreTest, AFailingBuilderPublishesNothing) {
  auto store = OpenStore();
  auto status = store->GetOrBuild("bad", EntryKind::kBlob, [] {
    return absl::StatusOr<std::vector<std::byte>>(absl::InvalidArgumentError("no such image"));
  });
  EXPECT_TRUE(absl::IsInvalidArgument(status.status()));
  EXPECT_TRUE(store->List().empty() ||
              std::all_of(store->List().begin(), store->List().end(),
                          [](const StoreEntryInfo& e) { return e.key != "bad"; }));
}

TEST_F(SharedStoreTest, ListShowsCompleteAndBrokenEntries) {
  auto store = OpenStore();
  ASSERT_TRUE(store->Put("good", EntryKind::kPackedTexture, Bytes("packed")).ok());
  ASSERT_TRUE(store->Put("broken", EntryKind::kBlob, Bytes("some bytes")).ok());
  fs::resize_file(EntryFile("broken"), 20);
  auto entries = store->List();
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_EQ(entries[0].key, "broken");
  EXPECT_NE(entries[0].state.find("shorter than a header"), std::string::npos) << entries[0].state;
  EXPECT_EQ(entries[1].key, "good");
  EXPECT_EQ(entries[1].state, "complete packed-texture");
}

TEST(SharedStoreOpen, AnUnwritableDirectoryIsAClearError) {
  auto store = SharedStore::Open("/proc/aperture-cannot-be-here");
  ASSERT_FALSE(store.ok());
  EXPECT_NE(store.status().message().find("/proc/aperture-cannot-be-here"), std::string::npos);
}

}  // namespace
}  // namespace aperture
