#!/usr/bin/env python3
"""Trains a pursuer with PPO on peg3d.vector_env against C++-side evaders, with numpy and PyTorch (CPU) only,
and saves it as an MLP policy file the C++ side plays (game/mlp_policy.hpp, docs/python.md).

    .venv/bin/python examples/ppo_pursuer.py --steps 2000000 --out ppo_pursuer.json \
        --opponent flee --opponent flee-apollonius --opponent robust_0_evader.json

With several --opponent, the games are split evenly among them (one vector env per evader, stepped in turn):
every update sees every opponent.

With several --scenario, the games take those starts in turn; a start named twice is played twice as often.
With several --map, one network trains on them all (one vector env per map and opponent).

The pursuer sees the 20 entries of its observation (no neighbours: a 1 v 1 game; 2 more with limited sight),
normalized by running statistics that are saved with the network. Its policy is a Gaussian about
action_bound * tanh(net(obs)) with a learnt standard deviation; the saved file keeps the mean and that deviation,
and says how the C++ side plays it (--play: the mean, or samples as in training). Autoreset is next-step: the step
that resets a game is no transition and is left out of the loss. --init starts from a saved network (its input
normalization then stays the saved one) to train it further, with --critic-warmup updates for its new critic.
"""

import argparse
import json
import math
import time

import numpy as np
import torch
from torch import nn

import peg3d
from peg3d.mappo import RunningStats, mlp, ppo_epochs, rollout_advantages


def save_policy(path, actor, stats, bound, observation, opponents, log_std, play="mean",
                trained_by="examples/ppo_pursuer.py"):
    """The actor as a policy file (peg3d.save_policy) recording the observation it reads, with the Gaussian's
    learnt standard deviation (action_std, rad): the C++ side plays the mean, or with play="sample" draws about it
    as training did."""
    layers = [(m.weight.detach().double().numpy(), m.bias.detach().double().numpy())
              for m in actor if isinstance(m, nn.Linear)]
    peg3d.save_policy(path, role="pursuer", observation=observation, layers=layers, action_bound=bound,
                      input_mean=stats.mean, input_std=stats.std, action_std=log_std.detach().exp().double().numpy(),
                      play=play, trained_by=trained_by, opponents=list(opponents))


def load_policy(path, actor, stats):
    """Starts `actor` and `stats` from a saved peg3d-mlp pursuer of the same shape (--init): to train on."""
    with open(path) as f:
        doc = json.load(f)
    linear = [m for m in actor if isinstance(m, nn.Linear)]
    shapes = [(len(l["weights"]), len(l["weights"][0])) for l in doc.get("layers", [])]
    if doc.get("format") != "peg3d-mlp" or shapes != [tuple(m.weight.shape) for m in linear]:
        raise SystemExit(f"--init {path}: not a peg3d-mlp network of layers {[tuple(m.weight.shape) for m in linear]}")
    with torch.no_grad():
        for m, layer in zip(linear, doc["layers"]):
            m.weight.copy_(torch.tensor(layer["weights"]))
            m.bias.copy_(torch.tensor(layer["bias"]))
    # The saved normalization, kept: the network was trained on inputs scaled so, and moving the scale under the
    # new games' inputs would change what it plays before it has learnt anything from them.
    stats.mean, stats.count = np.array(doc["input_mean"]), 1.0
    stats.m2 = np.array(doc["input_std"]) ** 2 - 1e-8
    stats.frozen = True
    return doc


class Games:
    """One vector env per map and evader policy, the games split among them, seen as one batch of pursuer arrays
    (games x pursuers x ...). A pursuer sees `neighbours` slots of the nearest other evaders and of its teammates
    (docs/python.md); the C++ side feeds a saved network the same."""

    def __init__(self, opponents, maps, num_envs, seed, neighbours=0, **kw):
        self.opponents = list(opponents)
        pairs = [(m, o) for m in maps for o in opponents]
        k = len(pairs)
        if num_envs < k:
            raise SystemExit(f"--num-envs {num_envs}: at least one game per map and opponent ({k})")
        self.sizes = [num_envs // k + (i < num_envs % k) for i in range(k)]
        self.envs = [peg3d.vector_env(map=m, num_envs=n, opponents={"evader": o}, seed=seed + i, neighbours=neighbours,
                                      **kw) for i, (n, (m, o)) in enumerate(zip(self.sizes, pairs))]
        e = self.envs[0]
        shapes = {(v.single_observation_space["pursuer"].shape, v.single_state_space.shape) for v in self.envs}
        if len(shapes) > 1:
            raise SystemExit(f"--map: the maps give pursuers of different numbers or observations ({sorted(shapes)})")
        self.pursuers = e.agent_counts["pursuer"]
        self.obs_size = e.single_observation_space["pursuer"].shape[-1]
        self.state_size = e.single_state_space.shape[0]
        self.bound = float(e.single_action_space["pursuer"].high[0, 0])
        # What a pursuer's network reads, as the saved file records it (every pursuer's is the first's here).
        self.observation = e.observation_segments["pursuer_0"]

    def reset(self, seed):
        obs = [e.reset(seed=seed + i)[0]["pursuer"] for i, e in enumerate(self.envs)]
        return np.concatenate(obs).astype(np.float64)

    def states(self):
        return np.concatenate([e.states() for e in self.envs]).astype(np.float64)

    def step(self, a):
        """Per game and pursuer: observation, reward, terminated, truncated and acted; then per game whether an
        evader was caught in this step, and whether this step reset it (its episode ended in the step before).
        A catch is read from the game, not from the reward, which has no capture term under some rewards."""
        out, lo = [], 0
        for e, n in zip(self.envs, self.sizes):
            obs, rew, term, trunc, info = e.step({"pursuer": a[lo:lo + n]})
            out.append((obs["pursuer"], rew["pursuer"], term["pursuer"], trunc["pursuer"], info["acted"]["pursuer"],
                        info["captured"]["evader"].any(axis=1), info["reset"].astype(bool)))
            lo += n
        parts = [np.concatenate(p) for p in zip(*out)]
        parts[0] = parts[0].astype(np.float64)
        return parts


def add_training_arguments(ap, map, steps, threads, out):
    """The flags examples/ppo_pursuer.py and examples/mappo_pursuers.py share."""
    ap.add_argument("--map", action="append",
                    help=f"a map to train on; repeat to train one network on several, their games split evenly "
                         f"(default: {map})")
    ap.add_argument("--scenario", action="append",
                    help="a start of the map; repeat to play several in turn, a name twice to play it twice as often "
                         "(default: the map's starts with its first start's teams)")
    ap.add_argument("--opponent", action="append",
                    help="an evader: flee, flee-apollonius, hide or a saved policy file; repeat to mix (default: flee)")
    ap.add_argument("--steps", type=int, default=steps, help="env steps (games x steps) to train for")
    ap.add_argument("--num-envs", type=int, default=32)
    ap.add_argument("--threads", type=int, default=threads)
    ap.add_argument("--rollout", type=int, default=128, help="steps per game per update")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--set", action="append", default=[], help="configuration override key=value")
    ap.add_argument("--init", help="start the actor from this saved peg3d-mlp network (of this script's shape)")
    ap.add_argument("--init-std", type=float, default=0.5,
                    help="the exploration's initial standard deviation, as a fraction of the steering bound")
    ap.add_argument("--critic-warmup", type=int, default=0,
                    help="updates that train the critic alone before the actor moves (for --init's new critic)")
    ap.add_argument("--neighbours", type=int, default=0,
                    help="slots of the nearest other evaders and of the teammates in each pursuer's observation")
    ap.add_argument("--play", choices=["mean", "sample"], default="mean",
                    help="how the C++ side plays the saved network: its mean action, or drawn from its Gaussian")
    ap.add_argument("--out", default=out)
    ap.set_defaults(default_map=map)


def make_games(args):
    return Games(args.opponent or ["flee"], args.map or [args.default_map], args.num_envs, args.seed,
                 neighbours=args.neighbours, threads=args.threads, scenario=args.scenario,
                 set=dict(s.split("=", 1) for s in args.set))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_training_arguments(ap, map="maps/paper.yaml", steps=1_000_000, threads=2, out="ppo_pursuer.json")
    args = ap.parse_args()
    torch.manual_seed(args.seed)
    torch.set_num_threads(1)
    env = make_games(args)
    n_obs, bound = env.obs_size, env.bound
    actor, critic = mlp([n_obs, 64, 64, 2], 0.01), mlp([n_obs, 64, 64, 1], 1.0)
    log_std = nn.Parameter(torch.full((2,), math.log(args.init_std * bound)))
    opt = torch.optim.Adam(list(actor.parameters()) + list(critic.parameters()) + [log_std], lr=3e-4)
    stats = RunningStats(n_obs)
    if args.init:
        load_policy(args.init, actor, stats)
    gamma, lam, clip = 0.99, 0.95, 0.2
    x = env.reset(seed=args.seed)[:, 0]
    N, T = args.num_envs, args.rollout
    done_steps, update, start = 0, 0, time.time()
    episodes = captures = 0
    while done_steps < args.steps:
        buf = {k: [] for k in ("x", "a", "logp", "r", "term", "trunc", "valid", "x2")}
        for _ in range(T):
            stats.update(x)
            xn = torch.as_tensor((x - stats.mean) / stats.std, dtype=torch.float32)
            with torch.no_grad():
                mu = bound * torch.tanh(actor(xn))
                dist = torch.distributions.Normal(mu, log_std.exp())
                a = dist.sample()
                logp = dist.log_prob(a).sum(-1)
            x2, rew, term, trunc, acted, caught, _ = (z[:, 0] if z.ndim > 1 else z
                                                       for z in env.step(a.numpy().astype(np.float64)[:, None, :]))
            buf["x"].append(xn.numpy()); buf["a"].append(a.numpy()); buf["logp"].append(logp.numpy())
            buf["r"].append(rew); buf["term"].append(term)
            buf["trunc"].append(trunc); buf["valid"].append(acted)
            buf["x2"].append(((x2 - stats.mean) / stats.std).astype(np.float32))
            episodes += int(((term | trunc) & acted).sum())
            captures += int((term & caught).sum())
            x = x2
        done_steps += N * T
        b = {k: np.asarray(v) for k, v in buf.items()}  # (T, N, ...)
        adv, ret = rollout_advantages(critic, b, "x", "x2", gamma, lam)
        keep = b["valid"].reshape(-1)
        xs, acts, logps = [torch.as_tensor(z.reshape((T * N,) + z.shape[2:])[keep]) for z in (b["x"], b["a"], b["logp"])]
        ppo_epochs(actor, critic, log_std, opt, bound, xs, acts, logps, xs,
                   torch.as_tensor(adv.reshape(-1)[keep], dtype=torch.float32),
                   torch.as_tensor(ret.reshape(-1)[keep], dtype=torch.float32), clip=clip,
                   train_actor=update >= args.critic_warmup)
        update += 1
        if update % 10 == 0 or done_steps >= args.steps:
            rate = captures / episodes if episodes else float("nan")
            print(json.dumps({"steps": done_steps, "updates": update, "episodes": episodes, "capture_rate": rate,
                              "seconds": round(time.time() - start, 1)}), flush=True)
            episodes = captures = 0
    save_policy(args.out, actor, stats, bound, env.observation, env.opponents, log_std, args.play)
    print(json.dumps({"saved": args.out, "seconds": round(time.time() - start, 1)}))


if __name__ == "__main__":
    main()
