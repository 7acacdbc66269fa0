#!/usr/bin/env bash
# Start a single-node Slurm cluster on localhost for the cluster test (tests/cluster):
#   munged + slurmctld + slurmd          (default; accounting disabled, use squeue for status)
#   + mariadbd + slurmdbd                (WITH_SLURMDBD=1; makes `sacct` work)
# Debian bookworm packages: munge slurmctld slurmd slurm-client [slurmdbd mariadb-server]
# (Slurm 22.05.8-4+deb12u3, munge 0.5.15-2+deb12u1, MariaDB 10.11).
# Must run as root. Works without systemd (daemons are started directly).
# PIDs: /run/munge/munged.pid /run/slurm/slurmctld.pid /run/slurm/slurmd.pid
#       [/run/mysqld/mysqld.pid /run/slurm/slurmdbd.pid]  -> stop.sh
# The pidfiles of the daemons this run starts (not those already running) are appended
# to $STARTED_FILE (default /run/slurm/kinetic-started), so that stop_slurm.sh stops only
# those.
set -euo pipefail
WITH_SLURMDBD="${WITH_SLURMDBD:-0}"
STARTED_FILE="${STARTED_FILE:-/run/slurm/kinetic-started}"
CLUSTER=localcluster
t0=$(date +%s)
log() { echo "[local-slurm +$(( $(date +%s) - t0 ))s] $*"; }
alive() { [ -f "$1" ] && kill -0 "$(cat "$1")" 2>/dev/null; }
started() { echo "$1" >> "$STARTED_FILE"; }

# --- packages -----------------------------------------------------------------
pkgs=(munge slurmctld slurmd slurm-client)
[ "$WITH_SLURMDBD" = 1 ] && pkgs+=(slurmdbd mariadb-server)
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if [ "${#missing[@]}" -gt 0 ]; then
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
log "packages ready"

# --- directories --------------------------------------------------------------
install -d -o munge -g munge -m 0755 /run/munge
install -d -o munge -g munge -m 0700 /var/log/munge /etc/munge
install -d -m 0755 /etc/slurm /run/slurm /var/spool/slurmctld /var/spool/slurmd /var/log/slurm
install -d -m 0755 "$(dirname "$STARTED_FILE")"; : > "$STARTED_FILE"

# --- slurm.conf -----------------------------------------------------------------
if [ "$WITH_SLURMDBD" = 1 ]; then
  ACCT="AccountingStorageType=accounting_storage/slurmdbd
AccountingStorageHost=localhost
AccountingStoragePort=6819
JobAcctGatherType=jobacct_gather/linux
JobAcctGatherFrequency=30"
else
  ACCT="AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none"
fi
cat > /etc/slurm/slurm.conf <<CONF
ClusterName=$CLUSTER
SlurmctldHost=localhost
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
MpiDefault=none
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
$ACCT
JobCompType=jobcomp/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
ReturnToService=2
SlurmctldPidFile=/run/slurm/slurmctld.pid
SlurmdPidFile=/run/slurm/slurmd.pid
SlurmctldPort=6817
SlurmdPort=6818
StateSaveLocation=/var/spool/slurmctld
SlurmdSpoolDir=/var/spool/slurmd
SlurmctldLogFile=/var/log/slurm/slurmctld.log
SlurmdLogFile=/var/log/slurm/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
# keep finished jobs visible to squeue/scontrol for 1 h: the snakemake slurm
# plugin can then poll with squeue (needs MinJobAge >= 3*init interval)
MinJobAge=3600
KillWait=5
InactiveLimit=0
Waittime=0
SlurmctldTimeout=30
SlurmdTimeout=30
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$(nproc) RealMemory=${SLURM_REALMEMORY_MB:-20000} State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF

# --- munge --------------------------------------------------------------------------
if [ ! -s /etc/munge/munge.key ]; then   # normally created by the package postinst
  dd if=/dev/urandom of=/etc/munge/munge.key bs=1 count=1024 status=none
  chown munge:munge /etc/munge/munge.key; chmod 0400 /etc/munge/munge.key
fi
alive /run/munge/munged.pid || { runuser -u munge -- /usr/sbin/munged --force; started /run/munge/munged.pid; }
for _ in $(seq 1 40); do munge -n | unmunge >/dev/null 2>&1 && break; sleep 0.25; done
munge -n | unmunge >/dev/null
log "munged pid $(cat /run/munge/munged.pid)"

# --- optional: mariadb + slurmdbd -------------------------------------------------------
if [ "$WITH_SLURMDBD" = 1 ]; then
  install -d -o mysql -g root -m 0755 /run/mysqld
  if ! alive /run/mysqld/mysqld.pid; then
    setsid /usr/sbin/mariadbd --user=mysql --datadir=/var/lib/mysql \
      --socket=/run/mysqld/mysqld.sock --pid-file=/run/mysqld/mysqld.pid \
      --bind-address=127.0.0.1 >/var/log/slurm/mariadb.log 2>&1 </dev/null &
    started /run/mysqld/mysqld.pid
  fi
  for _ in $(seq 1 120); do mariadb-admin ping >/dev/null 2>&1 && break; sleep 0.5; done
  mariadb-admin ping
  mariadb -e "CREATE DATABASE IF NOT EXISTS slurm_acct_db;
              CREATE USER IF NOT EXISTS 'slurm'@'localhost' IDENTIFIED BY 'slurmpw';
              GRANT ALL ON slurm_acct_db.* TO 'slurm'@'localhost'; FLUSH PRIVILEGES;"
  log "mariadbd pid $(cat /run/mysqld/mysqld.pid)"
  cat > /etc/slurm/slurmdbd.conf <<CONF
AuthType=auth/munge
DbdHost=localhost
DbdAddr=127.0.0.1
DbdPort=6819
SlurmUser=root
DebugLevel=info
LogFile=/var/log/slurm/slurmdbd.log
PidFile=/run/slurm/slurmdbd.pid
StorageType=accounting_storage/mysql
StorageHost=localhost
StoragePort=3306
StorageLoc=slurm_acct_db
StorageUser=slurm
StoragePass=slurmpw
CONF
  chmod 0600 /etc/slurm/slurmdbd.conf
  alive /run/slurm/slurmdbd.pid || { /usr/sbin/slurmdbd; started /run/slurm/slurmdbd.pid; }
  for _ in $(seq 1 60); do sacctmgr -n show cluster >/dev/null 2>&1 && break; sleep 0.5; done
  sacctmgr -n show cluster format=cluster | grep -qw "$CLUSTER" || sacctmgr -i add cluster "$CLUSTER" >/dev/null
  log "slurmdbd pid $(cat /run/slurm/slurmdbd.pid)"
fi

# --- slurmctld + slurmd ---------------------------------------------------------------
alive /run/slurm/slurmctld.pid || { /usr/sbin/slurmctld; started /run/slurm/slurmctld.pid; }  # daemonizes
for _ in $(seq 1 60); do scontrol ping 2>/dev/null | grep -q 'is UP' && break; sleep 0.5; done
scontrol ping | grep -q 'is UP'
alive /run/slurm/slurmd.pid || { /usr/sbin/slurmd -N localhost; started /run/slurm/slurmd.pid; }  # daemonizes
log "slurmctld pid $(cat /run/slurm/slurmctld.pid), slurmd pid $(cat /run/slurm/slurmd.pid)"
for _ in $(seq 1 60); do
  case "$(sinfo -h -n localhost -o '%T' 2>/dev/null)" in idle*|mixed*|allocated*) break ;; esac
  sleep 0.5
done
case "$(sinfo -h -n localhost -o '%T')" in
  idle*|mixed*|allocated*) ;;
  *) scontrol update nodename=localhost state=resume || true; sleep 2 ;;
esac
sinfo
log "cluster up"
