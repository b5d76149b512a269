#!/usr/bin/env python3
"""MAPPO for a team of pursuers on peg3d.vector_env, with numpy and PyTorch (CPU): one actor shared by every
pursuer, which sees its own observation alone, and one centralised critic, which sees the game's global state
(vector_env.states(): every agent's position, heading and activity, and the time) and which pursuer it values.
The evaders are played on the C++ side. The actor is saved as a peg3d-mlp file: peg-league plays it for every
pursuer of a team (--pursuer-entrant), beside the FACL and classic teams (docs/learning.md).

    .venv/bin/python examples/mappo_pursuers.py --map maps/pack.yaml --steps 2000000 --out mappo_pack.json \
        --opponent flee --opponent flee-apollonius

The actor sees its own observation; with --neighbours K it also sees the K nearest other evaders and the K nearest
teammates (docs/python.md, "Observations"), and the saved file records that observation, which the C++ side feeds
it in the league exactly as the batch did in training. Every pursuer's transition counts once it acted; next-step
autoreset's reset steps are left out, as in examples/ppo_pursuer.py, whose helpers this uses.
"""

import argparse
import json
import math
import time

import numpy as np
import torch
from torch import nn

from peg3d.mappo import RunningStats, mlp, ppo_epochs, rollout_advantages
from ppo_pursuer import add_training_arguments, load_policy, make_games, save_policy


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_training_arguments(ap, map="maps/pack.yaml", steps=2_000_000, threads=1, out="mappo_pursuers.json")
    args = ap.parse_args()
    torch.manual_seed(args.seed)
    torch.set_num_threads(1)
    env = make_games(args)
    K, n_obs, n_state, bound = env.pursuers, env.obs_size, env.state_size, env.bound
    actor = mlp([n_obs, 64, 64, 2], 0.01)
    critic = mlp([n_state + K, 128, 128, 1], 1.0)  # the state and a one-hot of the pursuer it values
    log_std = nn.Parameter(torch.full((2,), math.log(args.init_std * bound)))
    opt = torch.optim.Adam(list(actor.parameters()) + list(critic.parameters()) + [log_std], lr=3e-4)
    obs_stats, state_stats = RunningStats(n_obs), RunningStats(n_state)
    if args.init:
        load_policy(args.init, actor, obs_stats)
    eye = np.broadcast_to(np.eye(K), (args.num_envs, K, K))
    gamma, lam, clip = 0.99, 0.95, 0.2
    N, T = args.num_envs, args.rollout

    def critic_input(states):
        s = (states - state_stats.mean) / state_stats.std
        return torch.as_tensor(np.concatenate([np.repeat(s[:, None, :], K, axis=1), eye], axis=-1), dtype=torch.float32)

    x, s = env.reset(seed=args.seed), env.states()
    last_capture = np.zeros(N, dtype=bool)
    done_steps, update, start = 0, 0, time.time()
    games = captures = 0
    while done_steps < args.steps:
        buf = {k: [] for k in ("x", "a", "logp", "r", "term", "trunc", "valid", "c", "c2")}
        for _ in range(T):
            obs_stats.update(x.reshape(-1, n_obs))
            state_stats.update(s)
            xn = torch.as_tensor((x - obs_stats.mean) / obs_stats.std, dtype=torch.float32)  # (N, K, obs)
            with torch.no_grad():
                dist = torch.distributions.Normal(bound * torch.tanh(actor(xn)), log_std.exp())
                a = dist.sample()
                logp = dist.log_prob(a).sum(-1)
            c = critic_input(s)
            x2, rew, term, trunc, acted, caught, reset = env.step(a.numpy().astype(np.float64))
            s2 = env.states()
            buf["x"].append(xn.numpy()); buf["a"].append(a.numpy()); buf["logp"].append(logp.numpy())
            buf["r"].append(rew); buf["term"].append(term); buf["trunc"].append(trunc); buf["valid"].append(acted)
            buf["c"].append(c.numpy()); buf["c2"].append(critic_input(s2).numpy())
            # A game reset now ended in the step before: by a capture when its last step captured.
            games += int(reset.sum())
            captures += int((reset & last_capture).sum())
            last_capture = caught
            x, s = x2, s2
        done_steps += N * T
        b = {k: np.asarray(v) for k, v in buf.items()}  # (T, N, K, ...)
        adv, ret = rollout_advantages(critic, b, "c", "c2", gamma, lam)
        keep = b["valid"].reshape(-1)
        flat = lambda z: torch.as_tensor(z.reshape((T * N * K,) + z.shape[3:])[keep])  # noqa: E731
        ppo_epochs(actor, critic, log_std, opt, bound, flat(b["x"]), flat(b["a"]), flat(b["logp"]), flat(b["c"]),
                   torch.as_tensor(adv.reshape(-1)[keep], dtype=torch.float32),
                   torch.as_tensor(ret.reshape(-1)[keep], dtype=torch.float32), clip=clip,
                   train_actor=update >= args.critic_warmup)
        update += 1
        if update % 10 == 0 or done_steps >= args.steps:
            rate = captures / games if games else float("nan")
            print(json.dumps({"steps": done_steps, "updates": update, "games": games, "capture_rate": rate,
                              "seconds": round(time.time() - start, 1)}), flush=True)
            games = captures = 0
    save_policy(args.out, actor, obs_stats, bound, env.observation, env.opponents, log_std, args.play,
                trained_by="examples/mappo_pursuers.py")
    print(json.dumps({"saved": args.out, "seconds": round(time.time() - start, 1)}))


if __name__ == "__main__":
    main()
