#include "mosb/slurm.hpp"

#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "mosb/error.hpp"
#include "mosb/run.hpp"

TEST_CASE("shard i of N holds the queries k with k mod N = i - 1") {
  const auto shard = mosb::parse_shard("3/4");
  REQUIRE(shard);
  CHECK(shard->index == 3);
  CHECK(shard->count == 4);
  CHECK(shard->text() == "3/4");
  std::vector<std::uint64_t> mine;
  for (std::uint64_t q = 0; q < 10; ++q)
    if (shard->contains(q)) mine.push_back(q);
  CHECK(mine == std::vector<std::uint64_t>{2, 6});
  CHECK(shard->size(10) == 2);
  CHECK(mosb::Shard{1, 4}.size(10) == 3);
  CHECK(mosb::Shard{2, 4}.size(10) == 3);
  CHECK(mosb::Shard{4, 4}.size(10) == 2);
  // Every query is in exactly one shard.
  for (std::uint64_t q = 0; q < 23; ++q) {
    int owners = 0;
    for (std::uint64_t i = 1; i <= 5; ++i) owners += mosb::Shard{i, 5}.contains(q);
    CHECK(owners == 1);
  }
  for (const char* bad : {"0/4", "5/4", "1/0", "a/4", "1/", "/4", "1", "+1/4", "1/4 ", "-1/4"})
    CHECK_MESSAGE(!mosb::parse_shard(bad), bad);
  CHECK(mosb::parse_shard("1/1"));
}

TEST_CASE("the shard count comes from --shards or --queries-per-task") {
  CHECK(mosb::slurm_shard_count(100, 4, std::nullopt) == 4);
  CHECK(mosb::slurm_shard_count(100, std::nullopt, 30) == 4);
  CHECK(mosb::slurm_shard_count(100, std::nullopt, 100) == 1);
  CHECK(mosb::slurm_shard_count(100, std::nullopt, 1000) == 1);
  CHECK_THROWS_WITH_AS(mosb::slurm_shard_count(3, 4, std::nullopt),
                       doctest::Contains("only 3 queries"), mosb::Error);
  CHECK_THROWS_AS(mosb::slurm_shard_count(3, 0, std::nullopt), mosb::Error);
  CHECK_THROWS_AS(mosb::slurm_shard_count(3, std::nullopt, std::nullopt), mosb::Error);
  CHECK_THROWS_AS(mosb::slurm_shard_count(0, 1, std::nullopt), mosb::Error);
}

mosb::SlurmRun example_run() {
  mosb::SlurmRun run;
  run.directory = "/scratch/boa";
  run.mosb = "/opt/mosb/bin/mosb";
  run.working_directory = "/home/me/my solver";
  run.run_arguments = {"/data/grid.mosb",
                       "--view",
                       "Grid_2",
                       "--solver",
                       "./boa {instance} --query {source} {target}",
                       "--time-limit",
                       "60s"};
  run.instance = "/data/grid.mosb";
  run.query_set = "q";
  run.queries = 100;
  run.shards = 4;
  run.time_limit_seconds = 60;
  run.grace_seconds = 1;
  run.memory_limit_bytes = std::uint64_t{4} << 30;
  run.jobs = 2;
  run.throttle = 2;
  run.partition = "short";
  mosb::describe_run_tasks(run);
  return run;
}

TEST_CASE("--time and --mem follow the limits and the shard size") {
  auto run = example_run();
  // 25 queries a shard, 2 at a time: 13 rounds of 60 + 1 + 10 s, plus 5 minutes, in minutes.
  CHECK(mosb::slurm_time_seconds(run) == std::optional<std::uint64_t>(1260));
  CHECK(mosb::slurm_time_text(1260) == "0-00:21:00");
  CHECK(mosb::slurm_time_text(90061) == "1-01:01:01");
  CHECK(mosb::slurm_memory_mib(run) == std::optional<std::uint64_t>(2 * 4096 + 512));
  run.time_limit_seconds = 0;
  run.memory_limit_bytes = 0;
  CHECK(!mosb::slurm_time_seconds(run));
  CHECK(!mosb::slurm_memory_mib(run));
}

TEST_CASE("the array script is deterministic text with quoted arguments") {
  const auto run = example_run();
  const std::string script = mosb::slurm_script(run);
  CHECK(script == mosb::slurm_script(example_run()));
  CHECK(script.starts_with("#!/bin/sh\n"));
  CHECK(script.find("#SBATCH --array=1-4%2\n") != std::string::npos);
  CHECK(script.find("#SBATCH --cpus-per-task=2\n") != std::string::npos);
  CHECK(script.find("#SBATCH --time=0-00:21:00\n") != std::string::npos);
  CHECK(script.find("#SBATCH --mem=8704M\n") != std::string::npos);
  CHECK(script.find("#SBATCH --partition=short\n") != std::string::npos);
  CHECK(script.find("--account") == std::string::npos);
  CHECK(script.find("#SBATCH --output=/scratch/boa/shard-%a.log\n") != std::string::npos);
  CHECK(script.find("cd '/home/me/my solver'\n") != std::string::npos);
  CHECK(script.find("exec /opt/mosb/bin/mosb run /data/grid.mosb --view Grid_2 --solver "
                    "'./boa {instance} --query {source} {target}' --time-limit 60s --shard "
                    "\"$shard\"/4 --resume -o /scratch/boa/shard-\"$shard\".sol\n") !=
        std::string::npos);
  // A run without a task command has no script.
  auto bare = example_run();
  bare.task_command.clear();
  CHECK_THROWS_AS((void)mosb::slurm_script(bare), mosb::Error);
  // A name with a line break would put a command into the script's comment.
  auto injected = example_run();
  injected.query_set = "q\ntouch /tmp/pwned";
  mosb::describe_run_tasks(injected);
  CHECK_THROWS_WITH_AS((void)mosb::slurm_script(injected),
                       doctest::Contains("is not comment lines: 'touch /tmp/pwned"), mosb::Error);
  injected.task_comment = "# one line without its end";
  CHECK_THROWS_AS((void)mosb::slurm_script(injected), mosb::Error);
  injected.task_comment = "# a tab\tis a control character\n";
  CHECK_THROWS_AS((void)mosb::slurm_script(injected), mosb::Error);
  injected.task_comment.clear();
  CHECK(mosb::slurm_script(injected).starts_with("#!/bin/sh\n# Written by mosb "));
}

TEST_CASE("array lists and sbatch commands") {
  CHECK(mosb::slurm_array_list({1, 2, 3, 4}) == "1-4");
  CHECK(mosb::slurm_array_list({3}) == "3");
  CHECK(mosb::slurm_array_list({1, 3, 4, 5, 9}) == "1,3-5,9");
  const auto run = example_run();
  CHECK(mosb::sbatch_arguments(run, {1, 2, 3, 4}) ==
        std::vector<std::string>{"sbatch", "--parsable", "/scratch/boa/run.sbatch"});
  CHECK(mosb::sbatch_arguments(run, {2, 3}) == std::vector<std::string>{"sbatch", "--parsable",
                                                                        "--array=2-3%2",
                                                                        "/scratch/boa/run.sbatch"});
  CHECK(mosb::sbatch_command_text(run, {3}) ==
        "sbatch --parsable --array=3%2 /scratch/boa/run.sbatch >> /scratch/boa/jobs");
}

TEST_CASE("shards_to_resubmit: neither done nor queued, the queued ones left, in shard order") {
  std::vector<mosb::ShardState> shards(5);
  for (std::uint64_t i = 0; i < shards.size(); ++i) shards[i].index = i + 1;
  shards[0].file = mosb::ShardFile::done;
  shards[1].file = mosb::ShardFile::partial;
  shards[1].state = "RUNNING";
  shards[2].file = mosb::ShardFile::missing;
  shards[2].state = "FAILED";
  shards[3].file = mosb::ShardFile::damaged;
  shards[4].file = mosb::ShardFile::missing;
  shards[4].state = "PENDING";
  const auto r = mosb::shards_to_resubmit(shards);
  CHECK(r.resubmit == std::vector<std::uint64_t>{3, 4});
  CHECK(r.queued == std::vector<std::uint64_t>{2, 5});
  shards[0].state = "PENDING";  // done, even if the scheduler still lists it: nothing to do
  CHECK(mosb::shards_to_resubmit(shards).queued == std::vector<std::uint64_t>{2, 5});
}
