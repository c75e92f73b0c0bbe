#!/usr/bin/env bash
# A roslaunch process of its own, started as a node of another launch (test/graph/graph_split.test):
# the arguments are roslaunch's, without the __name:= and __log:= that roslaunch adds for a node.
# It finds the running master through ROS_MASTER_URI, as a second computer would.
args=()
for arg in "$@"; do
  case "$arg" in
    __name:=* | __log:=*) ;;
    *) args+=("$arg") ;;
  esac
done
exec roslaunch --wait "${args[@]}"
