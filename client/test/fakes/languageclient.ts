// Stand-in for `vscode-languageclient/node`: records how the client is built
// and answers workspace/executeCommand from a scripted handler.

export enum State {
  Stopped = 1,
  Running = 2,
  Starting = 3,
}

export enum TransportKind {
  stdio = 0,
  ipc = 1,
  pipe = 2,
  socket = 3,
}

export const ExecuteCommandRequest = { type: { method: 'workspace/executeCommand' } };

export interface RecordedRequest {
  method: string;
  params: { command: string; arguments: unknown[] };
}

export const clients: LanguageClient[] = [];

/** The error the next start() fails with, once. */
export const startFailures: Error[] = [];

/** Answers for workspace/executeCommand, by command id. */
export const serverAnswers = new Map<string, (args: unknown[]) => unknown>();

export class LanguageClient {
  state: State = State.Stopped;
  readonly requests: RecordedRequest[] = [];
  stopped = false;

  constructor(
    readonly id: string,
    readonly name: string,
    readonly serverOptions: unknown,
    readonly clientOptions: Record<string, unknown>,
  ) {
    clients.push(this);
  }

  private readonly stateListeners: Array<(event: { oldState: State; newState: State }) => void> = [];

  onDidChangeState(listener: (event: { oldState: State; newState: State }) => void) {
    this.stateListeners.push(listener);
    return { dispose: () => undefined };
  }

  private setState(state: State): void {
    const oldState = this.state;
    this.state = state;
    for (const listener of this.stateListeners) listener({ oldState, newState: state });
  }

  start(): Promise<void> {
    const failure = startFailures.shift();
    if (failure !== undefined) {
      this.setState(State.Stopped);
      return Promise.reject(failure);
    }
    this.setState(State.Running);
    return Promise.resolve();
  }

  stop(_timeout?: number): Promise<void> {
    this.setState(State.Stopped);
    this.stopped = true;
    return Promise.resolve();
  }

  dispose(_timeout?: number): Promise<void> {
    return this.stop();
  }

  sendRequest(type: { method: string }, params: RecordedRequest['params']): Promise<unknown> {
    this.requests.push({ method: type.method, params });
    const answer = serverAnswers.get(params.command);
    if (answer === undefined) {
      return Promise.reject(new Error(`unknown command ${params.command}`));
    }
    return Promise.resolve(answer(params.arguments));
  }
}
