# Sourced by the net tests: hosts in network namespaces on one machine. make_hosts <tag> <subnet>
# <count> makes <tag>-h1 .. <tag>-h<count>, each with eth0 at <subnet>.<i>/24 on a bridge in
# <tag>-sw and a multicast route (DDS discovery) on it, or exits 77 (skipped) without root. The
# caller's $pids (processes to stop) and $work (a folder to remove) are cleaned up at exit.
cleanup_hosts() {
  for p in "${pids[@]}"; do kill -CONT "$p" 2>/dev/null; kill -TERM "$p" 2>/dev/null; done
  sleep 0.5
  for p in "${pids[@]}"; do kill -KILL "$p" 2>/dev/null; done
  for n in $(ip netns list | awk '{print $1}' | grep "^$hosts_tag-"); do ip netns del "$n" 2>/dev/null; done
  rm -rf "$work"
}

make_hosts() {
  hosts_tag=$1
  local subnet=$2 count=$3 i n
  trap cleanup_hosts EXIT
  if [[ $(id -u) -ne 0 ]] || ! ip netns add "$hosts_tag-sw" 2>/dev/null; then
    echo "skipped: network namespaces need root (CAP_SYS_ADMIN, CAP_NET_ADMIN); run as root to test several hosts"
    exit 77
  fi
  ip -n "$hosts_tag-sw" link add br0 type bridge
  ip -n "$hosts_tag-sw" link set br0 up
  for i in $(seq "$count"); do
    n="h$i"
    ip netns add "$hosts_tag-$n"
    ip link add "$hosts_tag$n" type veth peer name eth0 netns "$hosts_tag-$n"
    ip link set "$hosts_tag$n" netns "$hosts_tag-sw"
    ip -n "$hosts_tag-sw" link set "$hosts_tag$n" master br0 up
    ip -n "$hosts_tag-$n" addr add "$subnet.$i/24" dev eth0
    ip -n "$hosts_tag-$n" link set eth0 up
    ip -n "$hosts_tag-$n" link set lo up
    ip -n "$hosts_tag-$n" route add 224.0.0.0/4 dev eth0  # DDS discovery's multicast goes out on eth0
  done
}
